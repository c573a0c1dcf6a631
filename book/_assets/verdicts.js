// Filters of the Verdicts table (book/_ext/fusion_book.py renders it); works offline, no library.
// A hash such as #verdicts-yang2012optimal (the chapters' In-brief links) preselects a source.
document.addEventListener("DOMContentLoaded", () => {
  const box = document.querySelector(".verdict-filters");
  const table = document.querySelector("table.verdicts-table");
  if (!box || !table) return;
  const rows = Array.from(table.querySelectorAll("tbody tr"));
  const selects = Array.from(box.querySelectorAll("select[data-filter]"));
  const count = box.querySelector(".verdict-count");
  const apply = () => {
    const want = selects.map((s) => s.value).filter((v) => v);
    let shown = 0;
    for (const row of rows) {
      const ok = want.every((cls) => row.classList.contains(cls));
      row.classList.toggle("verdict-hidden", !ok);
      if (ok) shown += 1;
    }
    if (count) count.textContent = `${shown} of ${rows.length} claims`;
  };
  const m = /^#verdicts-([\w-]+)/.exec(window.location.hash);
  if (m) {
    const src = selects.find((s) => s.dataset.filter === "src");
    if (src) src.value = `src-${m[1]}`;
  }
  selects.forEach((s) => s.addEventListener("change", apply));
  apply();
});
