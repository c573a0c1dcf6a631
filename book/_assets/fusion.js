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
