//! The few HTML pieces the reports are made of: escaped text, tables, sections and the page
//! around them (one file that opens offline: a small inline style, no script, nothing fetched).

use std::fmt::Write as _;

/// `text` safe inside an element or a quoted attribute.
pub(crate) fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// A table cell: its HTML content and an optional class.
pub(crate) struct Cell {
    html: String,
    class: Option<&'static str>,
}

impl Cell {
    pub fn text(text: &str) -> Self {
        Self::html(escape(text))
    }

    pub fn html(html: String) -> Self {
        Self { html, class: None }
    }

    pub fn with_class(self, class: &'static str) -> Self {
        Self {
            class: Some(class),
            ..self
        }
    }

    fn write(&self, out: &mut String, tag: &str) {
        match self.class {
            Some(class) => {
                let _ = write!(out, "<{tag} class=\"{class}\">{}</{tag}>", self.html);
            }
            None => {
                let _ = write!(out, "<{tag}>{}</{tag}>", self.html);
            }
        }
    }
}

/// A table with a header row, body rows and footer rows (summaries over the body).
#[derive(Default)]
pub(crate) struct Table {
    pub head: Vec<Cell>,
    pub rows: Vec<Vec<Cell>>,
    pub foot: Vec<Vec<Cell>>,
}

impl Table {
    /// A header of plain-text column names.
    pub fn with_head<'a>(names: impl IntoIterator<Item = &'a str>) -> Self {
        Self {
            head: names.into_iter().map(Cell::text).collect(),
            ..Self::default()
        }
    }

    pub fn to_html(&self) -> String {
        let mut out = String::from("<div class=\"scroll\"><table>\n<thead><tr>");
        for cell in &self.head {
            cell.write(&mut out, "th");
        }
        out.push_str("</tr></thead>\n<tbody>\n");
        write_rows(&mut out, &self.rows);
        out.push_str("</tbody>\n");
        if !self.foot.is_empty() {
            out.push_str("<tfoot>\n");
            write_rows(&mut out, &self.foot);
            out.push_str("</tfoot>\n");
        }
        out.push_str("</table></div>\n");
        out
    }
}

/// Rows whose first cell names the row (a header cell).
fn write_rows(out: &mut String, rows: &[Vec<Cell>]) {
    for row in rows {
        out.push_str("<tr>");
        for (i, cell) in row.iter().enumerate() {
            cell.write(out, if i == 0 { "th" } else { "td" });
        }
        out.push_str("</tr>\n");
    }
}

/// A titled part of the report, linked from its table of contents.
pub(crate) struct Section {
    pub id: &'static str,
    pub title: String,
    pub body: String,
}

impl Section {
    pub fn to_html(&self) -> String {
        format!(
            "<section id=\"{}\">\n<h2>{}</h2>\n{}</section>\n",
            self.id,
            escape(&self.title),
            self.body
        )
    }
}

/// A paragraph of plain text.
pub(crate) fn paragraph(text: &str) -> String {
    format!("<p>{}</p>\n", escape(text))
}

const STYLE: &str = "
body { font: 14px/1.45 system-ui, sans-serif; color: #222; max-width: 1500px; margin: 0 auto;
       padding: 16px 24px; }
h1 { font-size: 22px; margin-bottom: 4px; }
h2 { font-size: 18px; border-bottom: 1px solid #ccc; padding-bottom: 3px; margin-top: 32px; }
nav ol { columns: 2; column-gap: 48px; font-size: 13px; }
nav li { break-inside: avoid; }
.scroll { overflow-x: auto; }
table { border-collapse: collapse; font-variant-numeric: tabular-nums; }
th, td { border: 1px solid #ddd; padding: 3px 8px; text-align: right; white-space: nowrap; }
thead th { background: #f0f0f0; position: sticky; top: 0; }
th:first-child { text-align: left; }
tbody th, tfoot th { font-weight: normal; }
tfoot { background: #f7f7f7; }
td.fail { background: #f8d7da; color: #a00; font-weight: 600; }
td.part { background: #fff3cd; }
td.none { color: #999; }
td.reason { text-align: left; white-space: normal; font-family: monospace; }
small { color: #555; }
.plots { display: flex; flex-wrap: wrap; gap: 20px; }
figure { margin: 8px 0; }
svg { max-width: 100%; height: auto; }
#csr svg { max-width: min(100%, 720px); }
";

/// A whole page: `title`, the `overview` HTML under it, a table of contents and the sections.
pub(crate) fn page(title: &str, overview: &str, sections: &[Section]) -> String {
    let nav: String = sections
        .iter()
        .map(|p| format!("<li><a href=\"#{}\">{}</a></li>\n", p.id, escape(&p.title)))
        .collect();
    let body: String = sections.iter().map(Section::to_html).collect();
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{title}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<h1>{title}</h1>\n\
         {overview}<nav><ol>\n{nav}</ol></nav>\n{body}</body>\n</html>\n",
        title = escape(title),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_markup_and_quotes() {
        assert_eq!(
            escape(r#"<a href="x">'&'</a>"#),
            "&lt;a href=&quot;x&quot;&gt;&#39;&amp;&#39;&lt;/a&gt;"
        );
    }

    #[test]
    fn tables_name_rows_with_header_cells() {
        let mut table = Table::with_head(["method", "a<b"]);
        table
            .rows
            .push(vec![Cell::text("m"), Cell::text("1").with_class("fail")]);
        assert_eq!(
            table.to_html(),
            "<div class=\"scroll\"><table>\n<thead><tr><th>method</th><th>a&lt;b</th></tr></thead>\n\
             <tbody>\n<tr><th>m</th><td class=\"fail\">1</td></tr>\n</tbody>\n</table></div>\n"
        );
    }
}
