// What a reader would see as broken on a page of the site (tests/test_site.py runs it after MathJax has typeset).
// Returns {mathErrors, literalTex, placeholders, pageWidth, overflowing, badAlt}: each a list, empty when the page is sound.
() => {
  const CODE = "pre, code, script, style, mjx-container, textarea, kbd, samp, .highlight";
  const shown = el => el && el.checkVisibility({visibilityProperty: true});   // false inside a closed <details> too
  const texts = [];
  const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  while (walker.nextNode()) {
    const parent = walker.currentNode.parentElement;
    if (parent && !parent.closest(CODE) && shown(parent)) texts.push(walker.currentNode.textContent);
  }
  const literalTex = texts.filter(t => /\$|\\\(|\\\[|\\begin\{/.test(t)).map(t => t.trim().slice(0, 100));
  // an f-string field that was never formatted: {name}, {a // b}, {x:.2f}
  const placeholders = texts.join("\n").match(/\{[A-Za-z_][\w.]*(\s*[-+*\/%]+\s*[\w.]+)*(![rsa])?(:[^{}\s]*)?\}/g) || [];
  const mathErrors = [...document.querySelectorAll("mjx-merror")].map(e => (e.getAttribute("data-mjx-error") || e.textContent).slice(0, 100));
  const viewport = document.documentElement.clientWidth;
  const pageWidth = document.documentElement.scrollWidth > viewport + 1 ? [document.documentElement.scrollWidth] : [];
  // Wide content must scroll inside its own box, and that box must fit the text column.
  const column = (document.querySelector("article.bd-article") || document.querySelector("main") || document.body).getBoundingClientRect();
  const overflowing = [];
  for (const el of document.querySelectorAll("table, mjx-container[display='true'], pre, img")) {
    if (!shown(el)) continue;
    let box = ["auto", "scroll"].includes(getComputedStyle(el).overflowX) ? el : el.parentElement;
    while (box !== document.body && getComputedStyle(box).overflowX === "visible") box = box.parentElement;
    const scrolls = ["auto", "scroll"].includes(getComputedStyle(box).overflowX);
    const what = `${el.tagName.toLowerCase()} "${(el.textContent || el.getAttribute("alt") || "").trim().slice(0, 50)}"`;
    if (box === document.body ? el.getBoundingClientRect().right > column.right + 1 : !scrolls && el.scrollWidth > box.clientWidth + 1) {
      overflowing.push(`${what} is cut or wider than the column`);
    } else if (box !== document.body && el.getBoundingClientRect().left < box.getBoundingClientRect().left - box.scrollLeft - 1) {
      overflowing.push(`${what} overflows to the left of its box, where no scroll bar reaches`);
    } else if (box !== document.body && box.getBoundingClientRect().right > column.right + 1) {
      overflowing.push(`${what} scrolls in a box wider than the column`);
    }
  }
  const badAlt = [...document.querySelectorAll("img")].filter(i => {
    const alt = (i.getAttribute("alt") || "").trim();
    return alt.length < 8 || /\.(png|svg|jpe?g|gif)$/i.test(alt) || alt.includes("_images/") || alt.includes("see the text around");
  }).map(i => i.getAttribute("src"));
  return {mathErrors, literalTex, placeholders, pageWidth, overflowing, badAlt};
}
