// The site's own scripts (no asset comes from outside the site):
// 1. render the equations (pymdownx.arithmatex, generic mode) with the KaTeX served here;
// 2. label each table cell with its column's name, for the phone layout (assets/site.css).
document.addEventListener("DOMContentLoaded", function () {
  document.querySelectorAll(".arithmatex").forEach(function (element) {
    var text = element.textContent.trim();
    var display = text.startsWith("\\[");
    var tex = text.replace(/^\\[\[(]/, "").replace(/\\[\])]$/, "");
    katex.render(tex, element, { displayMode: display, throwOnError: false });
  });
  document.querySelectorAll("table").forEach(function (table) {
    var names = Array.from(table.querySelectorAll("thead th")).map(function (th) {
      return th.textContent.trim();
    });
    table.querySelectorAll("tbody tr").forEach(function (row) {
      Array.from(row.children).forEach(function (cell, index) {
        if (names[index]) cell.setAttribute("data-label", names[index]);
      });
    });
  });
});
