//! A table as typed columns: what the front ends that hand out columns (the Python package's
//! arrays, the lab's JSON) take from a [`Table`], so that their names and numbers are the CSV's.

use super::Table;
use serde::ser::{SerializeMap, SerializeSeq};
use serde::{Serialize, Serializer};

/// The cells of one column, typed as a CSV reader types them: whole numbers when every cell
/// is one, numbers when every cell is a number or empty (an empty cell is NaN), text
/// otherwise.
#[derive(Debug, Clone, PartialEq)]
pub enum Column {
    /// Every cell a whole number (`period`, `turns`).
    Integer(Vec<i64>),
    /// Every cell a number (`NaN`, `inf`) or empty (NaN).
    Number(Vec<f64>),
    /// Any other cells, as written (`stability`, `special`).
    Text(Vec<String>),
}

impl Column {
    /// The column of `cells`, typed (see [`Column`]).
    pub fn of(cells: Vec<String>) -> Self {
        if !cells.is_empty() {
            if let Ok(ints) = cells.iter().map(|c| c.parse::<i64>()).collect() {
                return Column::Integer(ints);
            }
        }
        let number = |c: &String| {
            if c.is_empty() {
                Ok(f64::NAN)
            } else {
                c.parse::<f64>()
            }
        };
        match cells.iter().map(number).collect() {
            Ok(numbers) => Column::Number(numbers),
            Err(_) => Column::Text(cells),
        }
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        match self {
            Column::Integer(v) => v.len(),
            Column::Number(v) => v.len(),
            Column::Text(v) => v.len(),
        }
    }

    /// Whether it has no cells.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl Serialize for Column {
    /// An array: whole numbers, numbers (a number that is not finite as null, which JSON
    /// has instead), or strings.
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Column::Integer(v) => v.serialize(s),
            Column::Number(v) => {
                let mut seq = s.serialize_seq(Some(v.len()))?;
                for x in v {
                    seq.serialize_element(&x.is_finite().then_some(*x))?;
                }
                seq.end()
            }
            Column::Text(v) => v.serialize(s),
        }
    }
}

/// A [`Table`] as columns, in the table's order, each named by its CSV column
/// ([`Table::columns`]) and holding the numbers its cells write (Rust's `Display` of an
/// `f64` reads back to the same number): the same names and the same numbers as the CSV.
/// Serialised as an object from column name to array (see [`Column`]'s serialisation).
#[derive(Debug, Clone, PartialEq)]
pub struct Columns {
    /// The column names and their cells.
    pub columns: Vec<(String, Column)>,
}

impl Columns {
    /// The columns of `table`.
    pub fn of<T: Table + ?Sized>(table: &T) -> Self {
        let names = table.columns();
        let mut cells: Vec<Vec<String>> = names
            .iter()
            .map(|_| Vec::with_capacity(table.len()))
            .collect();
        for i in 0..table.len() {
            for (column, cell) in cells.iter_mut().zip(table.row(i)) {
                column.push(cell);
            }
        }
        Self {
            columns: names
                .into_iter()
                .zip(cells.into_iter().map(Column::of))
                .collect(),
        }
    }

    /// The column `name`, if the table has it.
    pub fn get(&self, name: &str) -> Option<&Column> {
        self.columns.iter().find(|(n, _)| n == name).map(|(_, c)| c)
    }
}

impl Serialize for Columns {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.columns.len()))?;
        for (name, column) in &self.columns {
            map.serialize_entry(name, column)?;
        }
        map.end()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::cell;

    struct Three;

    impl Table for Three {
        fn columns(&self) -> Vec<String> {
            ["n", "x", "label"].map(String::from).to_vec()
        }
        fn len(&self) -> usize {
            3
        }
        fn row(&self, i: usize) -> Vec<String> {
            let x = [0.1, f64::NAN, 1e-7][i];
            let x = if i == 1 { String::new() } else { cell(x) };
            vec![i.to_string(), x, ["a", "", "c"][i].to_string()]
        }
    }

    #[test]
    fn columns_are_typed_as_the_csv_reads_them() {
        let c = Columns::of(&Three);
        assert_eq!(c.get("n"), Some(&Column::Integer(vec![0, 1, 2])));
        match c.get("x") {
            Some(Column::Number(x)) => {
                assert_eq!(x[0], 0.1);
                assert!(x[1].is_nan());
                assert_eq!(x[2], 1e-7);
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(
            c.get("label"),
            Some(&Column::Text(vec!["a".into(), "".into(), "c".into()]))
        );
        assert_eq!(
            serde_json::to_string(&c).unwrap(),
            r#"{"n":[0,1,2],"x":[0.1,null,1e-7],"label":["a","","c"]}"#
        );
    }
}
