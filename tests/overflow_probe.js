(function () {
  function measure() {
    var col = document.querySelector('article.bd-article') || document.querySelector('main');  // the text column
    document.body.setAttribute('data-fusion-viewport', String(window.innerWidth));  // the width it measured in
    if (!col) {
      NAMES.forEach(function (n) { document.body.setAttribute(n, '[]'); });
      return;
    }
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
    // figures: rendered size against the bitmap's natural size, and the alt text
    var figs = [];
    col.querySelectorAll('figure img, div.cell_output img').forEach(function (img) {
      var r = img.getBoundingClientRect();
      var link = img.closest('a[href]');
      figs.push({src: (img.getAttribute('src') || '').split('/').pop().slice(0, 16), alt: img.getAttribute('alt'),
                 width: r.width, height: r.height, naturalWidth: img.naturalWidth, naturalHeight: img.naturalHeight,
                 link: link ? link.getAttribute('href') : null, near: (img.closest('[id]') || {}).id || ''});
    });
    document.body.setAttribute('data-fusion-figures', JSON.stringify(figs));
    // inline formulas cut off: the formula reaches past the right edge of an ancestor that hides overflow
    var clipped = [];
    col.querySelectorAll('mjx-container:not([display="true"]) > mjx-math').forEach(function (m) {
      var mr = m.getBoundingClientRect();
      for (var a = m.parentElement; a && a !== col; a = a.parentElement) {
        var ov = getComputedStyle(a).overflowX;
        if (ov === 'visible') continue;
        var ar = a.getBoundingClientRect();
        if ((ov === 'hidden' || ov === 'clip') && (mr.right > ar.right + 1 || mr.left < ar.left - 1)) {
          clipped.push({near: (a.closest('[id]') || {}).id || '', width: Math.round(mr.width),
                        shown: Math.round(ar.width), text: (m.parentElement.textContent || '').trim().slice(0, 60)});
        }
        break;
      }
    });
    document.body.setAttribute('data-fusion-clipped-math', JSON.stringify(clipped));
    // published-vs-reproduced tables: a published or reproduced column header that starts beyond the right
    // edge of the column (to be scrolled to) or is cut by it
    var pvr = [];
    col.querySelectorAll('table').forEach(function (t) {
      var heads = Array.prototype.slice.call(t.querySelectorAll('thead th'));
      function txt(h) { return (h.textContent || '').trim().toLowerCase(); }
      var keys = heads.filter(function (h) {
        return /^(published|reproduced)\b/.test(txt(h)) && !/^reproduced\s*\/\s*published/.test(txt(h));
      });
      if (!keys.some(function (h) { return /^published/.test(txt(h)); }) ||
          !keys.some(function (h) { return /^reproduced/.test(txt(h)); })) return;
      keys.forEach(function (h) {
        if (!h.getClientRects().length) return;
        var hr = h.getBoundingClientRect();
        if (hr.right > right) {
          pvr.push({near: (t.closest('[id]') || {}).id || '', column: txt(h).slice(0, 30),
                    right: Math.round(hr.right), edge: Math.round(right)});
        }
      });
    });
    document.body.setAttribute('data-fusion-pvr-columns', JSON.stringify(pvr));
    // reading: the words a reader sees (closed <details> are not rendered, so not counted), and where the
    // introduction's findings list starts and ends (CSS px from the top of the page)
    var layout = {words: ((col.innerText || '').match(/\S+/g) || []).length, findings: null};
    var f = col.querySelector('ul.findings');
    if (f) {
      var fr = f.getBoundingClientRect();
      layout.findings = {top: Math.round(fr.top + window.scrollY), bottom: Math.round(fr.bottom + window.scrollY),
                         items: Array.prototype.map.call(f.querySelectorAll(':scope > li'),
                                                         function (li) { return li.innerText.trim(); })};
    }
    document.body.setAttribute('data-fusion-layout', JSON.stringify(layout));
  }
  var NAMES = ['data-fusion-overflow', 'data-fusion-figures', 'data-fusion-clipped-math', 'data-fusion-pvr-columns',
               'data-fusion-layout'];
  function go() {
    if (window.MathJax && MathJax.startup && MathJax.startup.promise) {
      MathJax.startup.promise.then(function () { setTimeout(measure, 200); });
    } else { setTimeout(measure, 500); }
  }
  if (document.readyState === 'complete') go(); else window.addEventListener('load', go);
  // measured again when the window is resized: after the book's own resize handlers (fusion.js: 150 ms)
  var resized = null;
  window.addEventListener('resize', function () { clearTimeout(resized); resized = setTimeout(measure, 500); });
})();
