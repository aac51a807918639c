// The search page's snippets are cut from the pages' text, where a formula is still its
// TeX source: typeset each snippet's whole formulas with the site's own MathJax, and cut
// a formula the snippet only holds part of.
(() => {
  const results = () => document.getElementById("search-results");
  if (!document.getElementById("search-documentation") && !results()) return;
  const root = document.documentElement.dataset.content_root || "";
  let loading = null;
  const mathjax = () => {
    if (!loading) {
      loading = new Promise((resolve) => {
        window.MathJax = {startup: {typeset: false, ready: () => {
          MathJax.startup.defaultReady(); resolve(); }}};
        const script = document.createElement("script");
        script.src = root + "_static/mathjax/tex-chtml.js";
        document.head.appendChild(script);
      });
    }
    return loading;
  };
  // the snippet's text with every formula whole: a part cut at either end is dropped
  const whole = (text) => {
    let t = text;
    const first = t.search(/\\[()[\]]/);
    if (first >= 0 && (t[first + 1] === ")" || t[first + 1] === "]")) {
      t = "…" + t.slice(first + 2);
    }
    const opens = [...t.matchAll(/\\[([]/g)].map((m) => m.index);
    const closes = [...t.matchAll(/\\[)\]]/g)].map((m) => m.index);
    if (opens.length > closes.length) t = t.slice(0, opens[opens.length - 1]) + "…";
    return t;
  };
  const typeset = (snippet) => {
    if (snippet.dataset.typeset) return;
    snippet.dataset.typeset = "yes";
    const text = whole(snippet.textContent);
    if (!/\\[([]/.test(text)) { if (text !== snippet.textContent) snippet.textContent = text; return; }
    snippet.textContent = text;
    mathjax().then(() => MathJax.typesetPromise([snippet]));
  };
  const watch = () => {
    const list = results();
    if (!list) return;
    new MutationObserver(() => list.querySelectorAll("p.context").forEach(typeset))
      .observe(list, {childList: true, subtree: true});
  };
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", watch);
  else watch();
})();
