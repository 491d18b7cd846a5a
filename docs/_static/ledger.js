// The ledger page: filter the table of checks by paper and by verdict (buttons with data-filter/data-value).
document.addEventListener("DOMContentLoaded", () => {
  const table = document.getElementById("ledger");
  if (!table) return;
  const rows = Array.from(table.tBodies[0].rows);
  const count = document.getElementById("ledger-count");
  const state = { paper: "", verdict: "" };
  const apply = () => {
    let shown = 0;
    for (const row of rows) {
      const visible = (!state.paper || row.dataset.paper === state.paper) &&
                      (!state.verdict || row.dataset.verdict === state.verdict);
      row.hidden = !visible;
      shown += visible ? 1 : 0;
    }
    count.textContent = String(shown);
  };
  for (const button of document.querySelectorAll("button[data-filter]")) {
    button.addEventListener("click", () => {
      state[button.dataset.filter] = button.dataset.value;
      for (const other of document.querySelectorAll(`button[data-filter="${button.dataset.filter}"]`)) {
        other.classList.toggle("active", other === button);
      }
      apply();
    });
  }
  apply();
});
