// The answer boxes of an exercise page: the reader's ID (kept in localStorage), the statement of their
// variant, the Check button with the verdict, progress, and "Save my answers". The data of each exercise is
// its bank (window.__courseBanks[id], one small script per exercise, on its page only); the verdict is
// decide.js's, the reading of the answer parse.js's.

import { decide, fromNested } from "./decide.js";
import { layout, parseAnswer } from "./parse.js";
import { decideSymbolic, parseFormulas, preview } from "./symbolic.js";

const BASIS = 2166136261;
const PRIME = 16777619;
const STORE = "jacobians-course:answers";
const ID_KEY = "jacobians-course:id";
/** IDs left from the notebook's template count as practice (course.classroom.grade.PLACEHOLDERS). */
const PLACEHOLDERS = new Set(["", "student-id", "your-id", "your student id", "0"]);

/** FNV-1a, 32 bits, of the UTF-8 bytes of `text` (course.exercises._bank.fnv1a32). */
export function fnv1a32(/** @type {string} */ text) {
  let h = BASIS;
  for (const b of new TextEncoder().encode(text)) h = Math.imul(h ^ b, PRIME) >>> 0;
  return h >>> 0;
}

/** The ID as the hash reads it (course.exercises._bank.normalise_id): spaces collapsed and trimmed, lower case. */
export function normaliseId(/** @type {string} */ id) {
  return String(id).replace(/\s+/g, " ").replace(/^ +| +$/g, "").toLowerCase();
}

/** The variant number an ID gets of an exercise (course.exercises._bank.variant_index). */
export function variantIndex(/** @type {string} */ exerciseId, /** @type {string} */ id, /** @type {number} */ size) {
  return fnv1a32(`${exerciseId}\n${normaliseId(id)}`) % size;
}

/** @returns {Record<string, any>} */
function banks() {
  const w = /** @type {any} */ (window);
  return w.__courseBanks || (w.__courseBanks = {});
}

/** The verdict on `text` for variant `k` of exercise `exerciseId` (what the Check button shows). */
export function checkText(/** @type {string} */ exerciseId, /** @type {number} */ k, /** @type {string} */ text) {
  const bank = banks()[exerciseId];
  if (!bank) return { correct: false, kind: "invalid", mistake: null, message: `No checking data for ${exerciseId}.` };
  if (bank.kind === "symbolic") {
    const formulas = parseFormulas(text);
    if (formulas.kind) return { correct: false, kind: formulas.kind, mistake: null, message: formulas.message, value: null };
    return { ...decideSymbolic(formulas, bank.variants[k], bank),
      value: { shape: formulas.shape, formulas: formulas.nodes.map((/** @type {any} */ n) => n.toString()) } };
  }
  const parsed = /** @type {any} */ (parseAnswer(text));
  if (parsed.kind) return { correct: false, kind: parsed.kind, mistake: null, message: parsed.message, value: null };
  return { ...decide(parsed, bank.variants[k], bank), value: parsed };
}

function load(/** @type {string} */ key, /** @type {any} */ fallback) {
  try {
    const v = window.localStorage.getItem(key);
    return v == null ? fallback : JSON.parse(v);
  } catch {
    return fallback;
  }
}

function save(/** @type {string} */ key, /** @type {any} */ value) {
  try {
    window.localStorage.setItem(key, JSON.stringify(value));
  } catch {
    /* private mode or full storage: progress is not kept, checking still works */
  }
}

const currentId = () => String(load(ID_KEY, "") || "");
const isPractice = (/** @type {string} */ id) => PLACEHOLDERS.has(normaliseId(id));

/** @type {Map<string, Promise<string>>} */
const statementLoads = new Map();

/** The typeset statement of variant `k` (its small script, written at build time with the page's MathJax
 * output: _ext/math_prerender.py), loaded once, on demand. */
function loadStatement(/** @type {HTMLElement} */ host, /** @type {string} */ exerciseId, /** @type {number} */ k) {
  const key = `${exerciseId}/${k}`;
  const w = /** @type {any} */ (window);
  const have = () => (w.__courseStatements || {})[key];
  if (typeof have() === "string") return Promise.resolve(/** @type {string} */ (have()));
  let p = statementLoads.get(key);
  if (!p) {
    p = new Promise((resolve, reject) => {
      const s = document.createElement("script");
      s.src = `${host.dataset.statements || ""}${k}.js`;
      s.onload = () => (typeof have() === "string" ? resolve(have()) : reject(new Error(`no statement in ${s.src}`)));
      s.onerror = () => { statementLoads.delete(key); reject(new Error(`could not load ${s.src}`)); };
      document.head.append(s);
    });
    statementLoads.set(key, p);
  }
  return p;
}

/** @type {Promise<unknown>[]} */
const pending = [];

/** Resolves when every statement asked for so far is on the page (for the browser tests). */
export function typesetDone() {
  return Promise.all(pending);
}

function el(/** @type {string} */ tag, /** @type {Record<string, string>} */ attrs = {}, /** @type {string} */ text = "") {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text) e.textContent = text;
  return e;
}

/** @type {Array<{refresh: () => void}>} */
const boxes = [];

function answersOf(/** @type {string} */ id) {
  const all = load(STORE, {});
  return (all && typeof all === "object" && all[normaliseId(id)]) || {};
}

function record(/** @type {string} */ id, /** @type {string} */ exerciseId, /** @type {any} */ entry) {
  const all = load(STORE, {}) || {};
  const key = normaliseId(id);
  all[key] = { ...(all[key] || {}), [exerciseId]: entry };
  save(STORE, all);
}

function progressText() {
  const id = currentId();
  const ids = [...document.querySelectorAll(".course-answer[data-exercise]")]
    .filter((b) => /** @type {HTMLElement} */ (b).dataset.checked === "page")
    .map((b) => /** @type {HTMLElement} */ (b).dataset.exercise || "");
  if (isPractice(id)) return `Practice: set your student ID to keep progress (${ids.length} exercises on this page checked here).`;
  const answers = answersOf(id);
  const right = ids.filter((x) => answers[x] && answers[x].correct).length;
  const tried = ids.filter((x) => answers[x] && !answers[x].correct).length;
  const all = Object.values(answers).filter((a) => a && a.correct).length;
  return `This page: ${right} right, ${tried} tried, ${ids.length - right - tried} untouched ` +
    `(the last answer counts). The course: ${all} right.`;
}

function download() {
  const id = currentId();
  const answers = answersOf(id);
  const out = { format: "jacobians-course-answers", version: 1, id, saved: new Date().toISOString(), answers: {} };
  for (const [ex, a] of Object.entries(answers)) {
    /** @type {any} */ (out.answers)[ex] = { text: a.text, value: a.value || null, variant: a.variant };
  }
  const blob = new Blob([JSON.stringify(out, null, 1)], { type: "application/json" });
  const a = el("a", { href: URL.createObjectURL(blob), download: `answers-${normaliseId(id).replace(/[^\w-]+/g, "_") || "practice"}.json` });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.getAttribute("href") || ""), 1000);
}

function idPanel() {
  const panel = el("section", { class: "course-id-panel", "aria-label": "Your student ID and progress" });
  const label = el("label", { for: "course-student-id" }, "Student ID");
  const input = /** @type {HTMLInputElement} */ (el("input", {
    id: "course-student-id", type: "text", autocomplete: "off", spellcheck: "false", maxlength: "200",
  }));
  input.value = isPractice(currentId()) ? "" : currentId();
  const set = el("button", { type: "button" }, "Use this ID");
  const clear = el("button", { type: "button" }, "Practice without an ID");
  const saveBtn = el("button", { type: "button" }, "Save my answers");
  const status = el("p", { class: "course-id-status", role: "status", "aria-live": "polite" });
  const progress = el("p", { class: "course-progress" });
  const apply = () => {
    save(ID_KEY, input.value.trim());
    status.textContent = isPractice(input.value) ? "No ID: practice variants." :
      `Every statement now shows the numbers of ID “${input.value.trim()}”.`;
    boxes.forEach((b) => b.refresh());
    progress.textContent = progressText();
  };
  set.addEventListener("click", apply);
  input.addEventListener("keydown", (e) => { if (e.key === "Enter") { e.preventDefault(); apply(); } });
  clear.addEventListener("click", () => { input.value = ""; apply(); });
  saveBtn.addEventListener("click", download);
  const row = el("div", { class: "course-id-row" });
  row.append(label, input, set, clear, saveBtn);
  panel.append(row, status, progress);
  progress.textContent = progressText();
  return { panel, progress };
}

let uid = 0;

/**
 * A grid of one input per entry, beside the text box (which stays the answer: the grid writes it as
 * [[a, b], [c, d]]). Tab and Shift+Tab go from cell to cell, the arrow keys move up and down (and left and
 * right at a cell's ends), Ctrl+Enter checks. Shown by its toggle button, for vectors and matrices only.
 */
function answerGrid(/** @type {HTMLTextAreaElement} */ box, /** @type {number} */ n, /** @type {() => void} */ onInput,
  /** @type {() => void} */ onCheck) {
  const toggle = el("button", { type: "button", class: "course-answer-grid-toggle", "aria-expanded": "false",
    "aria-controls": `course-answer-grid-${n}` }, "Enter in a grid");
  const wrap = el("div", { class: "course-answer-grid", id: `course-answer-grid-${n}`, hidden: "" });
  /** @type {number[]} */
  let shape = [];
  /** @type {HTMLInputElement[]} */
  let cells = [];
  const dims = () => (shape.length === 2 ? shape : [1, shape[0] || 1]);
  const write = () => {
    const [r, c] = dims();
    const rows = [];
    for (let i = 0; i < r; i++) rows.push("[" + cells.slice(i * c, (i + 1) * c).map((x) => x.value.trim()).join(", ") + "]");
    box.value = shape.length === 2 ? "[" + rows.join(",\n ") + "]" : rows[0];
    onInput();
  };
  const fill = () => {  // the cells from the text box, when its layout has the grid's shape
    const lay = /** @type {any} */ (layout(box.value));
    const flat = lay.rows ? lay.rows.flat() : [];
    const [r, c] = dims();
    const fits = lay.rows && flat.length === r * c && (shape.length !== 2 || lay.rows.length === r);
    cells.forEach((x, i) => { x.value = fits ? flat[i] : ""; });
  };
  const build = () => {
    wrap.textContent = "";
    const [r, c] = dims();
    const table = el("table", { role: "grid", "aria-label": shape.length === 2 ? `Your answer, ${r} rows by ${c} columns` :
      `Your answer, ${c} entries` });
    cells = [];
    for (let i = 0; i < r; i++) {
      const tr = el("tr");
      for (let j = 0; j < c; j++) {
        const td = el("td");
        const input = /** @type {HTMLInputElement} */ (el("input", {
          type: "text", inputmode: "text", spellcheck: "false", autocomplete: "off", size: "6",
          "aria-label": shape.length === 2 ? `row ${i + 1}, column ${j + 1}` : `entry ${j + 1}`,
        }));
        const at = i * c + j;
        input.addEventListener("input", write);
        input.addEventListener("keydown", (e) => {
          const move = (/** @type {number} */ to) => { if (to >= 0 && to < cells.length) { e.preventDefault(); cells[to].focus(); } };
          if (e.key === "Enter" && (e.ctrlKey || e.metaKey)) { e.preventDefault(); onCheck(); }
          else if (e.key === "ArrowDown" || e.key === "Enter") move(at + c);
          else if (e.key === "ArrowUp") move(at - c);
          else if (e.key === "ArrowRight" && input.selectionStart === input.value.length) move(at + 1);
          else if (e.key === "ArrowLeft" && input.selectionEnd === 0) move(at - 1);
        });
        td.append(input);
        tr.append(td);
        cells.push(input);
      }
      table.append(tr);
    }
    wrap.append(table);
    fill();
  };
  toggle.addEventListener("click", () => {
    const open = wrap.hidden;
    wrap.hidden = !open;
    toggle.setAttribute("aria-expanded", String(open));
    toggle.textContent = open ? "Hide the grid" : "Enter in a grid";
    if (open) { fill(); if (cells[0]) cells[0].focus(); }
  });
  box.addEventListener("input", () => { if (!wrap.hidden) fill(); });
  return {
    toggle, el: wrap,
    reshape(/** @type {number[]} */ s) {
      const same = s.length === shape.length && s.every((x, i) => x === shape[i]);
      shape = s;
      toggle.hidden = s.length === 0;
      if (s.length === 0) wrap.hidden = true;
      if (!same || !cells.length) build(); else fill();
    },
  };
}

function mountBox(/** @type {HTMLElement} */ host, /** @type {() => void} */ onChange) {
  const exerciseId = host.dataset.exercise || "";
  const bank = banks()[exerciseId];
  if (!bank) return;
  host.textContent = "";
  const n = ++uid;
  const head = el("p", { class: "course-answer-variant" });
  const newVariant = el("button", { type: "button", class: "course-answer-new" }, "New variant");
  const statement = el("div", { class: "course-answer-statement" });
  const label = el("label", { for: `course-answer-${n}` }, "Your answer");
  const symbolic = bank.kind === "symbolic";
  const help = el("span", { class: "course-answer-help", id: `course-answer-help-${n}` },
    bank.kind === "scalar" ? " (one number; fractions and pi are accepted)" :
      symbolic ? ` (formulas in ${bank.variants[0].symbols.join(", ")} as in Python, such as l1*cos(theta1); a ` +
        "matrix as [[row 1], [row 2], ...], one row a line, or sympy's Matrix([...]); Ctrl+Enter checks)" :
        " (numbers separated by commas or spaces, a matrix one row a line, or pasted from NumPy or MATLAB; " +
        "fractions and pi are accepted; Ctrl+Enter checks)");
  const box = /** @type {HTMLTextAreaElement} */ (el("textarea", {
    id: `course-answer-${n}`, rows: bank.kind === "scalar" ? "1" : "3", spellcheck: "false", autocomplete: "off",
    "aria-describedby": `course-answer-help-${n}`,
  }));
  // a formula's preview, as math.js reads it: typeset by the book's MathJax, which the first formula typed
  // loads (window.courseMath, _theme/math_menu.js; the page itself needs none), and plain text until it is ready
  const shown = el("div", { class: "course-answer-preview", "aria-live": "off" });
  let mathAsked = false;
  const showPreview = () => {
    if (!symbolic) return;
    shown.textContent = "";
    const parsed = box.value.trim() ? parseFormulas(box.value) : null;
    if (!parsed || parsed.kind) return;
    const p = preview(parsed);
    const w = /** @type {any} */ (window);
    if (!(w.MathJax && typeof w.MathJax.tex2chtmlPromise === "function") && w.courseMath && !mathAsked) {
      mathAsked = true;
      w.courseMath.load().then(showPreview, () => undefined);  // no MathJax: the plain-text preview stays
    }
    const table = el("table", { class: "course-answer-preview-table" });
    for (const row of p.rows) {
      const tr = el("tr");
      for (const cell of row) tr.append(el("td", {}, cell));
      table.append(tr);
    }
    shown.append(el("span", {}, "Read as: "), table);
    if (w.MathJax && typeof w.MathJax.tex2chtmlPromise === "function") {
      // the promise form: a TeX extension that loads on first use (autoload) makes the synchronous form throw
      const typed = box.value;
      w.MathJax.tex2chtmlPromise(p.tex, { display: false }).then((/** @type {Element} */ node) => {
        if (box.value !== typed) return;  // the reader typed on: a newer preview is on its way
        shown.textContent = "";
        shown.append(el("span", {}, "Read as: "), node);
        w.MathJax.startup.document.clear();
        w.MathJax.startup.document.updateDocument();
      }, () => undefined);  // TeX MathJax cannot read: the plain-text preview stays
    }
  };
  let previewTimer = 0;
  box.addEventListener("input", () => {
    window.clearTimeout(previewTimer);
    previewTimer = window.setTimeout(showPreview, 150);
  });
  const check = el("button", { type: "button", class: "course-answer-check" }, "Check");
  /** The shape of variant k's answer (the grid's rows and columns); [] for one number. */
  const gridShape = (/** @type {number} */ k) => {
    const v = bank.variants[k];
    if (bank.kind === "scalar") return [];
    return fromNested(symbolic ? v.ref[0] : v.ref).shape;
  };
  const grid = answerGrid(box, n, () => { showPreview(); }, () => run());
  const out = el("div", { class: "course-answer-verdict", role: "status", "aria-live": "polite" });
  const size = bank.variants.length;
  let practice = Math.floor(Math.random() * size);
  const variantNow = () => (isPractice(currentId()) ? practice : variantIndex(exerciseId, currentId(), size));

  const refresh = () => {
    const id = currentId();
    const k = variantNow();
    host.dataset.variant = String(k);
    if (isPractice(id)) {
      head.textContent = `Practice variant ${k + 1} of ${size} (no student ID set). `;
      head.append(newVariant);
    } else {
      head.textContent = `Your variant, for ID “${id}”:`;
    }
    if (statement.dataset.variant !== String(k)) statement.textContent = "";  // (no other variant's numbers)
    statement.dataset.variant = String(k);
    statement.setAttribute("aria-busy", "true");
    pending.push(loadStatement(host, exerciseId, k).then((html) => {
      if (host.dataset.variant !== String(k)) return;  // another variant was asked for meanwhile
      statement.innerHTML = html;  // the library's statement, typeset at build time
      statement.removeAttribute("aria-busy");
    }, () => {
      if (host.dataset.variant !== String(k)) return;
      statement.textContent = `The statement of variant ${k + 1} could not be loaded; the notebook shows it.`;
      statement.removeAttribute("aria-busy");
    }));
    const last = isPractice(id) ? null : answersOf(id)[exerciseId];
    box.value = last && last.variant === k ? last.text : "";
    grid.reshape(gridShape(k));
    showPreview();
    out.textContent = "";
    out.className = "course-answer-verdict";
  };
  newVariant.addEventListener("click", () => {
    practice = (practice + 1 + Math.floor(Math.random() * (size - 1))) % size;
    refresh();
    newVariant.focus();
  });
  const run = () => {
    const k = variantNow();
    const fb = checkText(exerciseId, k, box.value);
    out.textContent = "";
    out.className = `course-answer-verdict course-answer-${fb.kind}`;
    const headText = { correct: "✔ Correct", wrong: "✘ Not yet", empty: "… No answer yet", invalid: "? Cannot read this" };
    out.append(el("strong", {}, /** @type {any} */ (headText)[fb.kind] || "Not yet"), " ");
    if (fb.mistake) out.append(el("code", { class: "course-answer-mistake" }, fb.mistake), " ");
    out.append(el("span", {}, fb.message));
    const hint = bank.messages[bank.variants[k].hint];
    if (fb.kind === "wrong" && hint && !fb.message.includes(hint)) {
      const d = el("details", { class: "course-answer-hint" });
      d.append(el("summary", {}, "Hint"), el("span", {}, hint));
      out.append(d);
    }
    const id = currentId();
    if (!isPractice(id) && (fb.kind === "correct" || fb.kind === "wrong")) {
      record(id, exerciseId, { text: box.value, value: fb.value || null, variant: k, correct: fb.correct,
        mistake: fb.mistake, at: new Date().toISOString() });
    }
    onChange();
  };
  check.addEventListener("click", run);
  box.addEventListener("keydown", (e) => { if (e.key === "Enter" && (e.ctrlKey || e.metaKey)) { e.preventDefault(); run(); } });
  const field = el("div", { class: "course-answer-field" });
  field.append(box, check);
  host.append(head, statement, label, help, grid.toggle, grid.el, field, shown, out);
  host.dataset.checked = "page";
  boxes.push({ refresh });
  refresh();
}

export function mountAll() {
  const hosts = /** @type {HTMLElement[]} */ ([...document.querySelectorAll(".course-answer[data-exercise]")]);
  if (!hosts.length) return;
  const withBank = hosts.filter((h) => banks()[h.dataset.exercise || ""]);
  if (withBank.length) {
    const { panel, progress } = idPanel();
    // after the page's visible title (the theme also has a hidden one), else above the first box
    const title = [...document.querySelectorAll("article h1, main h1")]
      .find((h) => /** @type {HTMLElement} */ (h).offsetParent !== null);
    if (title) title.after(panel);
    else withBank[0].before(panel);
    const onChange = () => { progress.textContent = progressText(); };
    withBank.forEach((h) => mountBox(h, onChange));
    onChange();
  }
}
