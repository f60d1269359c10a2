//! The few HTML pieces the report is made of: escaped text, tables and sections.

use std::fmt::Write as _;

/// `text` safe inside an element or a quoted attribute.
pub(super) fn escape(text: &str) -> String {
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
pub(super) struct Cell {
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
pub(super) struct Table {
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
pub(super) struct Section {
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
pub(super) fn paragraph(text: &str) -> String {
    format!("<p>{}</p>\n", escape(text))
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
