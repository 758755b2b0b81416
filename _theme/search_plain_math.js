// Search results show math as plain words, not raw TeX.
//
// Sphinx's search (searchtools.js, Sphinx 7.4) builds each result's summary
// from the text of the page, where math is still TeX source such as
// \(\tau = J^T\mathcal F\), and cuts a 240-character window out of it, so a
// summary can start or end inside a formula. Typesetting cannot mend a cut
// formula; so before the text is taken, each formula is replaced by a plain
// reading of it (tau = J^T F becomes "τ = J^T F"). Loaded on every page; it
// acts only where the search page defines `Search`.
(function () {
  "use strict";
  const SYMBOLS = {
    alpha: "α", beta: "β", gamma: "γ", delta: "δ", epsilon: "ε", varepsilon: "ε", zeta: "ζ",
    eta: "η", theta: "θ", vartheta: "ϑ", iota: "ι", kappa: "κ", lambda: "λ", mu: "μ", nu: "ν",
    xi: "ξ", pi: "π", rho: "ρ", sigma: "σ", tau: "τ", upsilon: "υ", phi: "φ", varphi: "φ",
    chi: "χ", psi: "ψ", omega: "ω", Gamma: "Γ", Delta: "Δ", Theta: "Θ", Lambda: "Λ", Xi: "Ξ",
    Pi: "Π", Sigma: "Σ", Phi: "Φ", Psi: "Ψ", Omega: "Ω",
    times: "×", cdot: "·", in: "∈", to: "→", mapsto: "↦", rightarrow: "→", leftarrow: "←",
    le: "≤", leq: "≤", ge: "≥", geq: "≥", neq: "≠", ne: "≠", approx: "≈", equiv: "≡",
    partial: "∂", infty: "∞", pm: "±", sum: "Σ", prod: "Π", int: "∫", nabla: "∇",
    ldots: "…", dots: "…", cdots: "…", vdots: "⋮", ddots: "⋱", top: "ᵀ", perp: "⊥",
    quad: " ", qquad: "  ", sqrt: "√", circ: "∘", otimes: "⊗", oplus: "⊕", ell: "ℓ",
  };
  const DROP = new Set(["left", "right", "big", "Big", "bigg", "Bigg", "displaystyle", "mathrm",
    "mathbf", "mathcal", "mathit", "boldsymbol", "operatorname", "text", "textrm", "mathsf",
    "bar", "phantom", "limits", "nolimits"]);
  const ACCENTS = { dot: "\u0307", ddot: "\u0308", hat: "\u0302", tilde: "\u0303", vec: "\u20D7" };

  function plainTex(tex) {
    let s = tex;
    s = s.replace(/\\begin\{[a-z]*matrix\*?\}[\s\S]*?\\end\{[a-z]*matrix\*?\}/g, "[matrix]");
    s = s.replace(/\\begin\{[^}]*\}|\\end\{[^}]*\}/g, " ");
    s = s.replace(/\\mathbb\{R\}/g, "ℝ");
    s = s.replace(/\\(dot|ddot|hat|tilde|vec)\{([^{}]*)\}/g, (m, acc, arg) => arg + ACCENTS[acc]);
    s = s.replace(/\\(dot|ddot|hat|tilde|vec)\s*\\([A-Za-z]+)/g,
      (m, acc, name) => (SYMBOLS[name] || name) + ACCENTS[acc]);
    s = s.replace(/\\(dot|ddot|hat|tilde|vec)\s*([A-Za-z])/g, (m, acc, arg) => arg + ACCENTS[acc]);
    s = s.replace(/\\frac\{([^{}]*)\}\{([^{}]*)\}/g, "($1)/($2)");
    s = s.replace(/\\([A-Za-z]+)/g, (m, name) =>
      name in SYMBOLS ? SYMBOLS[name] : DROP.has(name) ? "" : name);
    s = s.replace(/\\[,;:! ]/g, " ").replace(/\\\\/g, "; ").replace(/&/g, " ");
    s = s.replace(/\\([{}\[\]()|])/g, "$1");
    s = s.replace(/[{}]/g, "");
    return s.replace(/\s+/g, " ").trim();
  }

  function stripDelimiters(text) {
    return text.replace(/^\s*(\\\(|\\\[|\$\$?)/, "").replace(/(\\\)|\\\]|\$\$?)\s*$/, "");
  }

  function patch() {
    if (typeof Search === "undefined" || !Search.htmlToText || Search._plainMath) return;
    const original = Search.htmlToText;
    Search.htmlToText = function (htmlString, anchor) {
      const doc = new DOMParser().parseFromString(htmlString, "text/html");
      doc.querySelectorAll(".math").forEach((el) => {
        // (a formula typeset at build time keeps its TeX in data-tex: _ext/math_prerender.py)
        el.textContent = " " + plainTex(el.dataset.tex || stripDelimiters(el.textContent)) + " ";
      });
      return original.call(this, doc.documentElement.outerHTML, anchor);
    };
    Search._plainMath = true;
  }

  window.jacobiansPlainTex = plainTex;   // for the browser test
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", patch);
  else patch();
})();
