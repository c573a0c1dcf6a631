(function () {
  function measure() {
    var col = document.querySelector('article.bd-article') || document.querySelector('main');  // the text column
    if (!col) { document.body.setAttribute('data-fusion-overflow', '[]'); return; }
    var right = col.getBoundingClientRect().right + 1;
    var out = [];
    var sel = 'table, mjx-container[display="true"], img, figure, div.cell_output pre, div.math';
    col.querySelectorAll(sel).forEach(function (el) {
      var w = el.scrollWidth, r = el.getBoundingClientRect();
      var box = el.closest('div.table-wrapper, div.pst-scrollable-table-container, div.output') || el.parentElement;
      var wide = r.right > right || (el.tagName === 'MJX-CONTAINER' && el.scrollWidth > col.clientWidth + 1)
                 || (el.tagName === 'TABLE' && el.scrollWidth > col.clientWidth + 1);
      if (wide) {
        var id = (el.closest('[id]') || {}).id || '';
        out.push({tag: el.tagName.toLowerCase(), near: id, width: Math.round(Math.max(w, r.width)),
                  column: Math.round(col.clientWidth), text: (el.textContent || '').trim().slice(0, 60)});
      }
    });
    // a numbered display equation whose formula and number together are wider than the column: MathJax
    // keeps the container inside the column, so the formula runs under its number and is cut
    col.querySelectorAll('div.math').forEach(function (d) {
      var m = d.querySelector('mjx-math'), n = d.querySelector('span.eqno');
      if (!m || !n) return;
      var w = m.getBoundingClientRect().width + n.getBoundingClientRect().width;
      if (w > col.clientWidth + 1) {
        out.push({tag: 'equation + number', near: d.id || '', width: Math.round(w),
                  column: Math.round(col.clientWidth), text: (d.textContent || '').trim().slice(0, 60)});
      }
    });
    document.body.setAttribute('data-fusion-overflow', JSON.stringify(out));
  }
  function go() {
    if (window.MathJax && MathJax.startup && MathJax.startup.promise) {
      MathJax.startup.promise.then(function () { setTimeout(measure, 200); });
    } else { setTimeout(measure, 500); }
  }
  if (document.readyState === 'complete') go(); else window.addEventListener('load', go);
})();
