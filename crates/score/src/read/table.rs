//! A table with named columns, read row by row, from a CSV file ([`Csv`]) or from
//! columns in memory ([`Columns`]: a DataFrame's, a structured array's), with the field
//! checks and `file:line: field` errors the readers share.

use std::borrow::Cow;
use std::io::Read;

use crate::error::ScoreError;

/// One column of a table in memory.
#[derive(Debug, Clone, Copy)]
pub enum Column<'a> {
    /// Floating-point values.
    Float(&'a [f64]),
    /// Integer values (names such as track numbers, or times in whole seconds).
    Int(&'a [i64]),
    /// Text values (names, statuses, or numbers as text).
    Text(&'a [String]),
}

impl<'a> Column<'a> {
    /// Row `i`'s cell (text trimmed, as a CSV reader trims it); `None` past the end.
    #[must_use]
    pub fn cell(&self, i: usize) -> Option<Cell<'a>> {
        Some(match *self {
            Self::Float(v) => Cell::Float(*v.get(i)?),
            Self::Int(v) => Cell::Int(*v.get(i)?),
            Self::Text(v) => Cell::Text(v.get(i)?.trim()),
        })
    }

    /// The number of values.
    #[must_use]
    pub fn len(&self) -> usize {
        match self {
            Self::Float(v) => v.len(),
            Self::Int(v) => v.len(),
            Self::Text(v) => v.len(),
        }
    }

    /// Whether the column has no value.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// One cell of a table: a CSV field's text, or a value of a column in memory.
#[derive(Debug, Clone, Copy)]
pub enum Cell<'a> {
    /// A field's text.
    Text(&'a str),
    /// A value of a [`Column::Float`].
    Float(f64),
    /// A value of a [`Column::Int`].
    Int(i64),
}

impl Cell<'_> {
    /// Whether it holds a value (an empty or blank CSV field holds none).
    #[must_use]
    pub fn is_given(self) -> bool {
        match self {
            Self::Text(raw) => !raw.trim().is_empty(),
            Self::Float(_) | Self::Int(_) => true,
        }
    }
}

/// The cell as text: a field as it is, a value as `{}` writes it.
impl std::fmt::Display for Cell<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Text(raw) => f.write_str(raw),
            Self::Float(v) => write!(f, "{v}"),
            Self::Int(i) => write!(f, "{i}"),
        }
    }
}

/// Where a table's header and rows come from.
pub(super) trait Source {
    /// The column names.
    fn header(&self) -> Vec<&str>;
    /// Moves to the next row; returns its line, `None` at the end.
    ///
    /// # Errors
    /// [`ScoreError::Syntax`] when a row cannot be read.
    fn next_row(&mut self) -> Result<Option<u64>, ScoreError>;
    /// The current row's cell of column `i`.
    fn cell(&self, i: usize) -> Option<Cell<'_>>;
}

/// A CSV file's rows (cells trimmed).
pub(super) struct Csv<R: Read> {
    file: String,
    rdr: csv::Reader<R>,
    header: csv::StringRecord,
    record: csv::StringRecord,
    line: u64,
}

impl<R: Read> Csv<R> {
    /// The CSV text of `reader`, `file` naming it in errors.
    ///
    /// # Errors
    /// [`ScoreError::Syntax`] when the header cannot be read.
    pub(super) fn new(reader: R, file: &str) -> Result<Self, ScoreError> {
        let mut rdr = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .from_reader(reader);
        let header = rdr.headers().map_err(|e| syntax(file, &e))?.clone();
        Ok(Self {
            file: file.to_owned(),
            rdr,
            header,
            record: csv::StringRecord::new(),
            line: 1,
        })
    }
}

impl<R: Read> Source for Csv<R> {
    fn header(&self) -> Vec<&str> {
        self.header.iter().collect()
    }

    fn next_row(&mut self) -> Result<Option<u64>, ScoreError> {
        match self.rdr.read_record(&mut self.record) {
            Ok(true) => {
                self.line = self
                    .record
                    .position()
                    .map_or(self.line + 1, csv::Position::line);
                Ok(Some(self.line))
            }
            Ok(false) => Ok(None),
            Err(e) => Err(syntax(&self.file, &e)),
        }
    }

    fn cell(&self, i: usize) -> Option<Cell<'_>> {
        self.record.get(i).map(Cell::Text)
    }
}

/// Columns in memory, row `i` at line `i + 2` (as if a CSV file with its header).
pub(super) struct Columns<'a> {
    names: &'a [String],
    columns: &'a [Column<'a>],
    rows: usize,
    /// The current row + 1 (0 before the first).
    next: usize,
}

impl<'a> Columns<'a> {
    /// The table of `columns` named by `names`.
    ///
    /// # Errors
    /// [`ScoreError::Syntax`] when names and columns differ in number or the columns in
    /// length.
    pub(super) fn new(
        names: &'a [String],
        columns: &'a [Column<'a>],
        file: &str,
    ) -> Result<Self, ScoreError> {
        let bad = |message: String| ScoreError::Syntax {
            file: file.to_owned(),
            line: 1,
            message,
        };
        if names.len() != columns.len() {
            return Err(bad(format!(
                "{} column names for {} columns",
                names.len(),
                columns.len()
            )));
        }
        let rows = columns.first().map_or(0, Column::len);
        if let Some((name, c)) = names.iter().zip(columns).find(|(_, c)| c.len() != rows) {
            return Err(bad(format!(
                "column '{name}' has {} rows, the first column {rows}",
                c.len()
            )));
        }
        Ok(Self {
            names,
            columns,
            rows,
            next: 0,
        })
    }
}

impl Source for Columns<'_> {
    fn header(&self) -> Vec<&str> {
        self.names.iter().map(String::as_str).collect()
    }

    fn next_row(&mut self) -> Result<Option<u64>, ScoreError> {
        if self.next >= self.rows {
            return Ok(None);
        }
        self.next += 1;
        Ok(Some(self.next as u64 + 1))
    }

    fn cell(&self, i: usize) -> Option<Cell<'_>> {
        self.columns.get(i)?.cell(self.next.checked_sub(1)?)
    }
}

/// A table with named columns: required ones first, then optional ones, by index.
pub(super) struct Table<'a, S: Source> {
    file: &'a str,
    source: S,
    names: Vec<&'static str>,
    cols: Vec<Option<usize>>,
    line: u64,
}

impl<'a, S: Source> Table<'a, S> {
    /// The table of `source` with the `required` and `optional` columns.
    ///
    /// # Errors
    /// [`ScoreError::MissingColumn`] naming the first required column missing.
    pub(super) fn new(
        source: S,
        file: &'a str,
        required: &[&'static str],
        optional: &[&'static str],
    ) -> Result<Self, ScoreError> {
        let cols = {
            let header = source.header();
            let find = |name: &str| header.iter().position(|h| *h == name);
            let mut cols = Vec::new();
            for &name in required {
                match find(name) {
                    Some(i) => cols.push(Some(i)),
                    None => {
                        return Err(ScoreError::MissingColumn {
                            file: file.to_string(),
                            column: name,
                        });
                    }
                }
            }
            cols.extend(optional.iter().map(|n| find(n)));
            cols
        };
        Ok(Self {
            file,
            source,
            names: required.iter().chain(optional).copied().collect(),
            cols,
            line: 1,
        })
    }

    /// The name of the table in errors.
    pub(super) fn file(&self) -> &'a str {
        self.file
    }

    /// Reads the next row; returns its line, `None` at the end.
    ///
    /// # Errors
    /// [`ScoreError::Syntax`] when a row cannot be read.
    pub(super) fn next_row(&mut self) -> Result<Option<u64>, ScoreError> {
        let line = self.source.next_row()?;
        if let Some(l) = line {
            self.line = l;
        }
        Ok(line)
    }

    fn cell(&self, col: usize) -> Option<Cell<'_>> {
        self.cols[col].and_then(|i| self.source.cell(i))
    }

    /// The text of column `col` (a number as Rust writes it), `None` when the table has no
    /// such column.
    pub(super) fn optional(&self, col: usize) -> Option<Cow<'_, str>> {
        self.cell(col).map(|c| match c {
            Cell::Text(s) => Cow::Borrowed(s),
            value => Cow::Owned(value.to_string()),
        })
    }

    /// A non-empty name.
    ///
    /// # Errors
    /// [`ScoreError::Field`] when empty.
    pub(super) fn name(&self, col: usize) -> Result<Cow<'_, str>, ScoreError> {
        match self.optional(col) {
            Some(s) if !s.is_empty() => Ok(s),
            _ => Err(self.field_error(col, "empty".to_string())),
        }
    }

    /// A finite number.
    ///
    /// # Errors
    /// [`ScoreError::Field`] for text that is not a number or a value that is not finite.
    #[allow(clippy::cast_precision_loss)] // integer columns: times and positions well below 2⁵³
    pub(super) fn number(&self, col: usize) -> Result<f64, ScoreError> {
        let v = match self.cell(col) {
            Some(Cell::Float(v)) => v,
            Some(Cell::Int(v)) => v as f64,
            Some(Cell::Text(s)) => s
                .parse::<f64>()
                .map_err(|_| self.field_error(col, format!("'{s}' is not a number")))?,
            None => return Err(self.field_error(col, "'' is not a number".to_owned())),
        };
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.field_error(col, format!("{v} is not a finite number")))
        }
    }

    /// An error at the current line, in column `col`.
    pub(super) fn field_error(&self, col: usize, message: String) -> ScoreError {
        ScoreError::Field {
            file: self.file.to_string(),
            line: self.line,
            field: self.names[col],
            message,
        }
    }
}

fn syntax(file: &str, e: &csv::Error) -> ScoreError {
    ScoreError::Syntax {
        file: file.to_string(),
        line: e.position().map_or(1, csv::Position::line),
        message: e.to_string(),
    }
}
