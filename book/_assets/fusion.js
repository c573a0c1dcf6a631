// fusion-book: small reading aids on top of the theme (issue 28).
//
// Published-vs-reproduced tables (a "published ..." and a "reproduced ..." column header): their
// other columns (the difference, a ratio, notes) are marked `fusion-secondary`, which fusion.css
// hides on a phone, so that the published and reproduced values fit the screen. A column-group
// header above hidden columns is narrowed while they are hidden, so headers stay over their columns.
(function () {
  function text(el) { return (el.textContent || '').trim().toLowerCase(); }
  function colClass(el) {
    var m = (el.getAttribute('class') || '').match(/\bcol(\d+)\b/);
    return m ? m[1] : null;
  }
  function mark(table) {
    var heads = Array.prototype.slice.call(table.querySelectorAll('thead th'));
    var hasPub = heads.some(function (h) { return /^published\b/.test(text(h)); });
    var hasRep = heads.some(function (h) { return /^reproduced\b/.test(text(h)); });
    if (!hasPub || !hasRep) return;
    // the key columns: the published and reproduced values (not a ratio of the two); the rest
    // (difference, ratio, notes) is secondary
    var hidden = {};
    heads.forEach(function (h) {
      var c = colClass(h), t = text(h);
      if (c === null || h.hasAttribute('colspan') || !/\bcol_heading\b/.test(h.className)) return;
      var key = /^(published|reproduced)\b/.test(t) && !/^reproduced\s*\/\s*published/.test(t);
      if (!key) hidden[c] = true;
    });
    var cols = Object.keys(hidden);
    if (!cols.length) return;
    table.classList.add('fusion-pvr');
    cols.forEach(function (c) {
      table.querySelectorAll('td.col' + c + ', th.col' + c).forEach(function (el) {
        if (!el.hasAttribute('colspan')) el.classList.add('fusion-secondary');
      });
    });
    // group headers spanning hidden columns: the narrower span applies only while they are hidden
    heads.forEach(function (h) {
      var span = parseInt(h.getAttribute('colspan') || '1', 10), c = colClass(h);
      if (span < 2 || c === null) return;
      var n = 0;
      for (var j = +c; j < +c + span; j++) if (hidden[j]) n++;
      if (n && n < span) { h.setAttribute('data-fusion-span', String(span)); h.setAttribute('data-fusion-phone-span', String(span - n)); }
    });
  }
  function spans() {
    var phone = window.matchMedia('(max-width: 600px)').matches;
    document.querySelectorAll('th[data-fusion-span]').forEach(function (h) {
      h.setAttribute('colspan', phone ? h.getAttribute('data-fusion-phone-span') : h.getAttribute('data-fusion-span'));
    });
  }
  function go() {
    document.querySelectorAll('div.cell_output table').forEach(mark);
    spans();
    window.matchMedia('(max-width: 600px)').addEventListener('change', spans);
  }
  if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', go); else go();
})();

// Formulas wider than the text (a phone): MathJax 3 does not break lines, so a formula that does not fit
// is set smaller, down to 70 % of its size inline and 80 % on its own line (where it can scroll, so it
// stays larger); an inline formula that still does not fit scrolls sideways
// (class fusion-scroll; the theme's span.math otherwise hides its overflow, and a display formula
// already scrolls in its box). Recomputed when the window is resized.
(function () {
  var SMALLEST_INLINE = 0.7, SMALLEST_DISPLAY = 0.8;
  function contentWidth(el) {
    while (el && /^inline/.test(getComputedStyle(el).display)) el = el.parentElement;
    if (!el) return 0;
    var cs = getComputedStyle(el);
    return el.clientWidth - parseFloat(cs.paddingLeft) - parseFloat(cs.paddingRight);
  }
  function fit() {
    document.querySelectorAll('span.math > mjx-container, div.math > mjx-container').forEach(function (c) {
      var inline = c.parentElement.tagName === 'SPAN', math = c.querySelector('mjx-math');
      if (!math) return;
      if (c.hasAttribute('data-fusion-size')) c.style.fontSize = c.getAttribute('data-fusion-size');
      if (inline) c.parentElement.classList.remove('fusion-scroll');
      var avail = inline ? contentWidth(c.parentElement.parentElement) : c.clientWidth;
      var need = math.getBoundingClientRect().width;
      if (!avail || need <= avail) return;
      if (!c.hasAttribute('data-fusion-size')) c.setAttribute('data-fusion-size', c.style.fontSize || '');
      var scale = Math.max(inline ? SMALLEST_INLINE : SMALLEST_DISPLAY, 0.98 * avail / need);
      c.style.fontSize = (parseFloat(getComputedStyle(c).fontSize) * scale).toFixed(2) + 'px';
      if (inline && need * scale > avail) c.parentElement.classList.add('fusion-scroll');
    });
  }
  function start() {
    if (window.MathJax && MathJax.startup && MathJax.startup.promise) MathJax.startup.promise.then(fit);
    var timer = null;
    window.addEventListener('resize', function () { clearTimeout(timer); timer = setTimeout(fit, 150); });
  }
  if (document.readyState === 'complete') start(); else window.addEventListener('load', start);
})();
