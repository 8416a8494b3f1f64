//! Markdown tables of the reproductions' reports: alignment, padding, escaped `|`, short rows.

use tvf_papers::markdown::Table;

#[test]
fn tables_render_with_alignment_and_padding() {
    let mut table = Table::new(["mesh", "time"]);
    table.row(["a|b", "1 s"]);
    table.row(["c"]);
    let text = table.to_markdown();
    assert_eq!(
        text,
        "| mesh | time |\n|---|---:|\n| a\\|b | 1 s |\n| c |  |\n"
    );
}
