// MathJax for pymdownx.arithmatex (generic mode): \( ... \) inline, \[ ... \] display.
// MathJax itself is javascripts/mathjax/tex-svg.js, shipped with the site (see its README.md):
// SVG output draws every glyph as a path, so the pages need no font and no network.
//
// Nothing else is ever fetched: tex-svg.js holds all the pages need. Its contextual menu can
// switch on accessibility add-ons (explorer, collapsible, assistive MathML), which MathJax loads
// as components, and the speech engine it bundles (SRE) fetches its locale files from
// cdn.jsdelivr.net. The menu is off, its add-on settings (stored by a browser too) are off, and
// the component loader and the speech engine's locale loader refuse every file.
const notShipped = (what) =>
  Promise.reject(new Error(`${what}: not shipped with the docs, which load nothing`));

window.SREfeature = { custom: (locale) => notShipped(`speech locale ${locale}`) };

window.MathJax = {
  loader: {
    require: (file) => notShipped(file),
  },
  tex: {
    inlineMath: [["\\(", "\\)"]],
    displayMath: [["\\[", "\\]"]],
    processEscapes: true,
    processEnvironments: true,
  },
  svg: {
    fontCache: "global",
  },
  options: {
    ignoreHtmlClass: ".*|",
    processHtmlClass: "arithmatex",
    enableMenu: false,
    menuOptions: {
      settings: { explorer: false, collapsible: false, assistiveMml: false },
    },
  },
};

document$.subscribe(() => {
  MathJax.startup.output.clearCache();
  MathJax.typesetClear();
  MathJax.texReset();
  MathJax.typesetPromise();
});
