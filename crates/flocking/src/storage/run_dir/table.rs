//! A reader for flocking's own numeric CSV files: a header line of column names, then rows of
//! numbers separated by commas (no quoting, no empty fields). Errors name the file and the line.

use std::fs;
use std::path::{Path, PathBuf};

use super::read_error::ReadError;

/// A numeric table: column names and rows of numbers, each as long as the header.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Table {
    /// The column names of the header, trimmed.
    pub(crate) header: Vec<String>,
    /// The rows, in file order, with the line number (1-based) each came from.
    pub(crate) rows: Vec<(usize, Vec<f64>)>,
    /// The file it was read from (for error messages).
    pub(crate) path: PathBuf,
}

impl Table {
    /// Reads `path`. Blank lines are skipped; every other line must have as many fields as the
    /// header, each a number (`nan`, `inf` and `-inf` are accepted, as Rust prints them).
    pub(crate) fn read(path: &Path) -> Result<Self, ReadError> {
        let text = fs::read_to_string(path).map_err(|e| ReadError::io(path, e))?;
        Self::parse(&text, path)
    }

    /// Parses the text of a file (`path` is only used in error messages).
    pub(crate) fn parse(text: &str, path: &Path) -> Result<Self, ReadError> {
        let error = |line: usize, message: String| ReadError::Parse {
            path: path.to_path_buf(),
            line,
            message,
        };
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(k, line)| (k + 1, line.trim()))
            .filter(|(_, line)| !line.is_empty());
        let Some((header_line, header)) = lines.next() else {
            return Err(error(1, "the file is empty: expected a header line".into()));
        };
        let header: Vec<String> = header.split(',').map(|s| s.trim().to_owned()).collect();
        if let Some(k) = header.iter().position(String::is_empty) {
            return Err(error(
                header_line,
                format!("column {} of the header has no name", k + 1),
            ));
        }
        let mut rows = Vec::new();
        for (line_number, line) in lines {
            let mut row = Vec::with_capacity(header.len());
            for (k, field) in line.split(',').enumerate() {
                let field = field.trim();
                let Some(name) = header.get(k) else {
                    return Err(error(
                        line_number,
                        format!(
                            "expected {} fields (as the header), found {}",
                            header.len(),
                            line.split(',').count()
                        ),
                    ));
                };
                let value = field.parse::<f64>().map_err(|_| {
                    error(
                        line_number,
                        format!("field {} ({name:?}) is {field:?}, not a number", k + 1),
                    )
                })?;
                row.push(value);
            }
            if row.len() != header.len() {
                return Err(error(
                    line_number,
                    format!(
                        "expected {} fields (as the header), found {}",
                        header.len(),
                        row.len()
                    ),
                ));
            }
            rows.push((line_number, row));
        }
        Ok(Self {
            header,
            rows,
            path: path.to_path_buf(),
        })
    }

    /// The index of the column `name`, if the header has it.
    pub(crate) fn column_index(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    /// An error about `line` of this table's file.
    pub(crate) fn error_at(&self, line: usize, message: impl Into<String>) -> ReadError {
        ReadError::Parse {
            path: self.path.clone(),
            line,
            message: message.into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_header_and_rows() {
        let t = Table::parse("a,b\n1,2.5\n\n-3,nan\n", Path::new("x.csv")).unwrap();
        assert_eq!(t.header, ["a", "b"]);
        assert_eq!(t.rows.len(), 2);
        assert_eq!(t.rows[0], (2, vec![1.0, 2.5]));
        assert_eq!(t.rows[1].0, 4);
        assert!(t.rows[1].1[1].is_nan());
    }

    #[test]
    fn short_and_long_lines_are_refused_with_their_line() {
        let e = Table::parse("a,b\n1\n", Path::new("x.csv")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "x.csv:2: expected 2 fields (as the header), found 1"
        );
        let e = Table::parse("a,b\n1,2,3\n", Path::new("x.csv")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "x.csv:2: expected 2 fields (as the header), found 3"
        );
    }

    #[test]
    fn empty_file_is_refused() {
        let e = Table::parse("\n\n", Path::new("x.csv")).unwrap_err();
        assert!(e.to_string().contains("empty"), "{e}");
    }
}
