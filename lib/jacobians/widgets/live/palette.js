// @ts-check
// The live views' colours, in one place (the sliders' range comes with each view's model, from
// jacobians.widgets.live.LIMIT).
//
// The views draw the library's Okabe–Ito palette (jacobians.plotting.style.PALETTE). Each colour is a
// CSS custom property on the view (.jac-live): the SVG and the HTML of a view say "var(--jl-blue)", and
// the value follows the page's theme:
//   - the book (pydata-sphinx-theme) sets html[data-theme="dark"] or "light";
//   - JupyterLab sets body[data-jp-theme-light="false"] in a dark theme;
//   - anywhere else (a deck, a plain page) the reader's prefers-color-scheme decides.
// A view paints its own ground (GROUND), so every ratio below is taken against a known colour:
// a line or a shape at least 3:1 (WCAG 1.4.11), text at least 4.5:1 (WCAG 1.4.3), in both modes
// (tests/test_live_palette_contrast.py computes them all from this table).

/** The ground a view paints under itself, light and dark (the dark one is the book theme's own). */
export const GROUND = { light: "#ffffff", dark: "#121212" };

/**
 * @typedef {object} Swatch one colour of the views
 * @property {string} hex the library's colour it stands for (upper case), or "" for a view-only shade
 * @property {[string, string]} line as a line or a shape: [on the light ground, on the dark ground], >= 3:1
 * @property {[string, string]} text as text: [light, dark], >= 4.5:1
 */

// Okabe–Ito's orange (#E69F00, 2.2:1 on white), sky blue (#56B4E9, 2.3:1) and the grey #999999 (2.8:1)
// are too light for a line on white: the light mode draws them darker, same hue. On the dark ground
// Okabe–Ito's blue (#0072B2, 3.6:1) is too dark for text and black is invisible: the dark mode draws
// a lighter blue, and black becomes the light grey of the text.
/** @type {Readonly<Record<string, Swatch>>} */
export const SWATCHES = {
  vermillion: { hex: "#D55E00", line: ["#D55E00", "#E8731A"], text: ["#B35000", "#E8731A"] },
  blue: { hex: "#0072B2", line: ["#0072B2", "#3C9BE0"], text: ["#0072B2", "#3C9BE0"] },
  green: { hex: "#009E73", line: ["#009E73", "#009E73"], text: ["#007A5A", "#00B386"] },
  purple: { hex: "#CC79A7", line: ["#CC79A7", "#CC79A7"], text: ["#9E5584", "#D99BC0"] },
  orange: { hex: "#E69F00", line: ["#B07800", "#E69F00"], text: ["#9A6700", "#E69F00"] },
  sky: { hex: "#56B4E9", line: ["#3388BB", "#56B4E9"], text: ["#2A6F9E", "#56B4E9"] },
  grey: { hex: "#999999", line: ["#767676", "#999999"], text: ["#767676", "#ADADAD"] },
  plum: { hex: "#7A3D63", line: ["#7A3D63", "#D99BC0"], text: ["#7A3D63", "#D99BC0"] },
  ink: { hex: "#000000", line: ["#000000", "#E0E0E0"], text: ["#000000", "#E0E0E0"] },
  soft: { hex: "#4D4D4D", line: ["#4D4D4D", "#BDBDBD"], text: ["#333333", "#C8C8C8"] },
};

/** Shades that carry no meaning (grids, panel borders): no contrast asked of them. [light, dark]. */
/** @type {Readonly<Record<string, [string, string]>>} */
export const DECOR = {
  paper: [GROUND.light, GROUND.dark],
  grid: ["#DDDDDD", "#3A3A3A"],
  faint: ["#EBEBEB", "#2A2A2A"],
  border: ["#BBBBBB", "#5C5C5C"],
  // text on a dot filled with a palette colour: black on the light mode's darker shades, the dark ground's
  // colour on the dark mode's lighter ones (tests/browser/test_live_theme.py measures it on the dot)
  "on-colour": ["#000000", "#121212"],
};

// Other spellings of a colour in the library or the views: the swatch they are drawn with.
/** @type {Readonly<Record<string, string>>} */
const ALIASES = { "#888888": "grey", "#333333": "soft", BLACK: "ink", WHITE: "paper", "#FFFFFF": "paper" };

/** @type {Map<string, string>} the library's hex (upper case) -> the swatch's name */
const BY_HEX = new Map([
  ...Object.entries(SWATCHES).map(([name, s]) => /** @type {[string, string]} */ ([s.hex, name])),
  ...Object.entries(ALIASES),
]);

/** @param {string} c @returns {string | undefined} the swatch or decor name of colour c */
function nameOf(c) {
  const ref = /^var\(--jl-([a-z-]+)\)$/.exec(String(c)); // a colour graphic() already gave
  if (ref && (ref[1] in SWATCHES || ref[1] in DECOR)) return ref[1];
  const k = String(c).toUpperCase();
  if (k in SWATCHES || k.toLowerCase() in SWATCHES) return k.toLowerCase();
  if (k.toLowerCase() in DECOR) return k.toLowerCase();
  return BY_HEX.get(k);
}

/**
 * A colour of the palette (the library's hex, or a swatch's name) as a line or a shape on the view's
 * ground, in the page's mode: a CSS var() reference. A colour the palette does not know is kept as given.
 * @param {string} c
 * @returns {string}
 */
export function graphic(c) {
  const name = nameOf(c);
  return name ? `var(--jl-${name})` : c;
}

/**
 * The same colour as text: the darker (light mode) or lighter (dark mode) shade that reaches 4.5:1.
 * @param {string} c
 * @returns {string}
 */
export function ink(c) {
  const name = nameOf(c);
  return name && name in SWATCHES ? `var(--jl-${name}-text)` : graphic(c);
}

/** A colour at opacity a in [0, 1] (a tint of a table cell), from any of the forms above. @param {string} c @param {number} a */
export const tint = (c, a) => `color-mix(in srgb, ${graphic(c)} ${Math.round(100 * a)}%, transparent)`;

/** The colours by role, as the views draw them (var() references). */
export const PALETTE = Object.freeze({
  link: graphic("blue"), joint: graphic("ink"), muted: graphic("grey"), velocity: graphic("vermillion"),
  force: graphic("green"), path: graphic("orange"), ok: graphic("green"), warning: graphic("orange"),
  singular: graphic("vermillion"), space: graphic("orange"), body: graphic("sky"), geometric: graphic("green"),
  analytic: graphic("purple"), fg: graphic("ink"), bg: graphic("paper"), grid: graphic("grid"),
  faint: graphic("faint"), border: graphic("border"), soft: graphic("soft"), onColour: graphic("on-colour"),
});

/** Colours of Jacobian columns 1, 2, 3, ... (cycled): jacobians.plotting.style.COLUMN_COLORS. */
export const COLUMN_COLORS = ["vermillion", "blue", "green", "purple", "orange", "sky", "ink"].map(graphic);
/** @param {number} i @returns {string} */
export const columnColor = (i) => COLUMN_COLORS[i % COLUMN_COLORS.length];

/** The frame axes x, y, z (red-free Okabe–Ito: vermillion, bluish green, blue). */
export const AXIS_COLORS = ["vermillion", "green", "blue"].map(graphic);

/** @param {0 | 1} mode 0 light, 1 dark @returns {string} the custom properties of that mode */
function properties(mode) {
  const out = [];
  for (const [name, s] of Object.entries(SWATCHES)) out.push(`--jl-${name}:${s.line[mode]};--jl-${name}-text:${s.text[mode]}`);
  for (const [name, d] of Object.entries(DECOR)) out.push(`--jl-${name}:${d[mode]}`);
  return out.join(";");
}

/**
 * The style of the palette: light by default, dark where the page is dark. A view paints its ground
 * and its text colour, so its ratios hold on any page; `color-scheme` gives its controls (sliders,
 * selects) the matching native look.
 */
export const THEME_CSS = `
.jac-live{${properties(0)};color:var(--jl-ink);background:var(--jl-paper);color-scheme:light;accent-color:var(--jl-blue)}
html[data-theme=dark] .jac-live,body[data-jp-theme-light=false] .jac-live{${properties(1)};color-scheme:dark}
@media (prefers-color-scheme:dark){html:not([data-theme]) body:not([data-jp-theme-light]) .jac-live{${properties(1)};color-scheme:dark}}
`;
