//! Arrow IPC tables in `eval` (feature `arrow`): file (`.arrow`, `.feather`) and stream
//! (`.arrows`) formats in and out, the same values as CSV bit for bit, column types, nulls.

use crate::common::{polbrdf, stderr};
use arrow_array::cast::AsArray;
use arrow_array::types::Float64Type;
use arrow_array::{
    ArrayRef, Float32Array, Float64Array, Int32Array, RecordBatch, StringArray, UInt8Array,
};
use arrow_schema::{DataType, Field, Schema};
use std::path::Path;
use std::sync::Arc;

/// The bytes of an Arrow IPC table (`stream`: stream format, else file format) of `columns`,
/// in record batches of `batch` rows.
pub fn arrow_bytes(columns: &[(&str, ArrayRef)], stream: bool, batch: usize) -> Vec<u8> {
    let schema = Arc::new(Schema::new(
        columns
            .iter()
            .map(|(n, a)| Field::new(*n, a.data_type().clone(), true))
            .collect::<Vec<_>>(),
    ));
    let rows = columns.first().map_or(0, |c| c.1.len());
    let mut out = Vec::new();
    {
        let batches: Vec<RecordBatch> = (0..rows.div_ceil(batch.max(1)).max(1))
            .map(|k| {
                let start = (k * batch).min(rows);
                let n = batch.min(rows - start);
                RecordBatch::try_new(
                    schema.clone(),
                    columns.iter().map(|c| c.1.slice(start, n)).collect(),
                )
                .unwrap()
            })
            .collect();
        if stream {
            let mut w = arrow_ipc::writer::StreamWriter::try_new(&mut out, &schema).unwrap();
            for b in &batches {
                w.write(b).unwrap();
            }
            w.finish().unwrap();
        } else {
            let mut w = arrow_ipc::writer::FileWriter::try_new(&mut out, &schema).unwrap();
            for b in &batches {
                w.write(b).unwrap();
            }
            w.finish().unwrap();
        }
    }
    out
}

/// A geometry table of the four angles (Float64) and `extra` columns, as Arrow bytes.
pub fn geometry_arrow(extra: Vec<(&str, ArrayRef)>) -> Vec<u8> {
    let f = |v: &[f64]| -> ArrayRef { Arc::new(Float64Array::from(v.to_vec())) };
    let mut cols = vec![
        ("theta_i_deg", f(&[30.0, 40.0])),
        ("phi_i_deg", f(&[0.0, 10.0])),
        ("theta_r_deg", f(&[30.0, 20.0])),
        ("phi_r_deg", f(&[180.0, 90.0])),
    ];
    cols.extend(extra);
    arrow_bytes(&cols, false, 1024)
}

/// Every column of an Arrow IPC file: name and (Float64 as f64 bits, or text).
fn read_arrow(path: &Path) -> Table {
    let f = std::fs::File::open(path).unwrap();
    let r = arrow_ipc::reader::FileReader::try_new(f, None).unwrap();
    let schema = r.schema();
    let mut cols: Table = schema
        .fields()
        .iter()
        .map(|f| {
            let v = if f.data_type() == &DataType::Utf8 {
                Err(vec![])
            } else {
                assert_eq!(f.data_type(), &DataType::Float64, "{}", f.name());
                Ok(vec![])
            };
            (f.name().clone(), v)
        })
        .collect();
    for b in r {
        let b = b.unwrap();
        for (i, (_, c)) in cols.iter_mut().enumerate() {
            match c {
                Ok(v) => v.extend(
                    b.column(i)
                        .as_primitive::<Float64Type>()
                        .values()
                        .iter()
                        // CSV writes −0 as 0; Arrow (like .npy) keeps the sign.
                        .map(|x| (x + 0.0).to_bits()),
                ),
                Err(v) => v.extend(
                    b.column(i)
                        .as_string::<i32>()
                        .iter()
                        .map(|s| s.unwrap().to_string()),
                ),
            }
        }
    }
    cols
}

/// Every column of an `eval` CSV: name and values (numbers as f64 bits, else text).
fn read_csv(path: &Path) -> Table {
    let mut r = csv::Reader::from_path(path).unwrap();
    let headers: Vec<String> = r.headers().unwrap().iter().map(str::to_string).collect();
    let rows: Vec<csv::StringRecord> = r.records().map(Result::unwrap).collect();
    headers
        .iter()
        .enumerate()
        .map(|(i, h)| {
            let texts: Vec<String> = rows.iter().map(|r| r[i].to_string()).collect();
            let nums: Option<Vec<u64>> = texts
                .iter()
                .map(|t| t.parse::<f64>().ok().map(f64::to_bits))
                .collect();
            (h.clone(), nums.ok_or(texts))
        })
        .collect()
}

/// A CSV of `n` varied valid geometries with a `label` (text) and a `wavelength_um` column.
fn geometry_csv(n: usize) -> String {
    let mut s = String::from("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,wavelength_um,label\n");
    for k in 0..n {
        let x = k as f64;
        s += &format!(
            "{},{},{},{},{},r{k}\n",
            (x * 0.37) % 89.0,
            (x * 7.1) % 360.0 - 180.0,
            (x * 0.53 + 3.0) % 89.0,
            x * 1.3 % 360.0,
            0.4 + (x * 0.001) % 1.0
        );
    }
    s
}

/// The CSV table as Arrow: numbers Float64 (as the CSV text parses), text Utf8.
fn csv_to_arrow(csv_text: &str, stream: bool, batch: usize) -> Vec<u8> {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("t.csv");
    std::fs::write(&p, csv_text).unwrap();
    let cols = read_csv(&p);
    let arrays: Vec<(&str, ArrayRef)> = cols
        .iter()
        .map(|(n, c)| -> (&str, ArrayRef) {
            match c {
                Ok(bits) => (
                    n.as_str(),
                    Arc::new(Float64Array::from(
                        bits.iter().map(|b| f64::from_bits(*b)).collect::<Vec<_>>(),
                    )),
                ),
                Err(t) => (n.as_str(), Arc::new(StringArray::from(t.clone()))),
            }
        })
        .collect();
    arrow_bytes(&arrays, stream, batch)
}

fn eval(input: &Path, output: &Path) {
    let out = polbrdf(&[
        "eval",
        "--material",
        "paint",
        "--input",
        input.to_str().unwrap(),
        "--output",
        output.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
}

type Table = Vec<(String, Result<Vec<u64>, Vec<String>>)>;

/// Asserts two tables are equal, naming the first column and row that differ.
fn same(a: &Table, b: &Table, what: &str) {
    let names = |t: &Table| t.iter().map(|c| c.0.clone()).collect::<Vec<_>>();
    assert_eq!(names(a), names(b), "{what}");
    for ((name, x), (_, y)) in a.iter().zip(b) {
        if x != y {
            let row = match (x, y) {
                (Ok(x), Ok(y)) => (0..x.len().max(y.len()))
                    .find(|&k| x.get(k) != y.get(k))
                    .map(|k| {
                        format!(
                            "row {k}: {:?} vs {:?}",
                            x.get(k).map(|b| f64::from_bits(*b)),
                            y.get(k).map(|b| f64::from_bits(*b))
                        )
                    }),
                (Err(x), Err(y)) => (0..x.len().max(y.len()))
                    .find(|&k| x.get(k) != y.get(k))
                    .map(|k| format!("row {k}: {:?} vs {:?}", x.get(k), y.get(k))),
                _ => Some("numbers vs text".into()),
            };
            panic!("{what}: column `{name}` differs at {row:?}");
        }
    }
}

#[test]
fn csv_to_arrow_to_eval_to_arrow_equals_csv_to_csv_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // More than one chunk (65 536 rows), in input batches that straddle the chunks.
    let text = geometry_csv(70_000);
    std::fs::write(d.join("g.csv"), &text).unwrap();
    std::fs::write(d.join("g.arrow"), csv_to_arrow(&text, false, 30_000)).unwrap();
    std::fs::write(d.join("g.arrows"), csv_to_arrow(&text, true, 50_000)).unwrap();
    eval(&d.join("g.csv"), &d.join("ref.csv"));
    let reference = read_csv(&d.join("ref.csv"));
    assert_eq!(reference.len(), 6 + 19);
    // Arrow in, Arrow out; CSV in, Arrow out; stream in, file out.
    for (input, output) in [
        ("g.arrow", "a.arrow"),
        ("g.csv", "c.arrow"),
        ("g.arrows", "s.feather"),
    ] {
        eval(&d.join(input), &d.join(output));
        same(
            &read_arrow(&d.join(output)),
            &reference,
            &format!("{input} → {output}"),
        );
    }
    // Arrow in, CSV out: the same values as CSV in.
    eval(&d.join("g.arrow"), &d.join("a.csv"));
    same(&read_csv(&d.join("a.csv")), &reference, "g.arrow → a.csv");
    // Stream out, read back as input of the same columns.
    eval(&d.join("g.arrow"), &d.join("o.arrows"));
    let r = arrow_ipc::reader::StreamReader::try_new(
        std::fs::File::open(d.join("o.arrows")).unwrap(),
        None,
    )
    .unwrap();
    let rows: usize = r.map(|b| b.unwrap().num_rows()).sum();
    assert_eq!(rows, 70_000);
}

#[test]
fn float32_integer_and_text_columns_are_read_and_passed_through() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let bytes = arrow_bytes(
        &[
            (
                "theta_i_deg",
                Arc::new(Float32Array::from(vec![30.0f32, 40.5])),
            ),
            ("phi_i_deg", Arc::new(Int32Array::from(vec![0, -10]))),
            ("theta_r_deg", Arc::new(UInt8Array::from(vec![30u8, 20]))),
            ("phi_r_deg", Arc::new(Float64Array::from(vec![180.0, 90.0]))),
            ("name", Arc::new(StringArray::from(vec!["a", "b,\"c\""]))),
        ],
        false,
        1,
    );
    std::fs::write(d.join("g.feather"), bytes).unwrap();
    std::fs::write(
        d.join("g.csv"),
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,name\n30,0,30,180,a\n40.5,-10,20,90,\"b,\"\"c\"\"\"\n",
    )
    .unwrap();
    eval(&d.join("g.feather"), &d.join("a.csv"));
    eval(&d.join("g.csv"), &d.join("c.csv"));
    assert_eq!(read_csv(&d.join("a.csv")), read_csv(&d.join("c.csv")));
    eval(&d.join("g.feather"), &d.join("a.arrow"));
    let cols = read_arrow(&d.join("a.arrow"));
    assert_eq!(
        cols[4],
        ("name".into(), Err(vec!["a".into(), "b,\"c\"".into()]))
    );
    assert_eq!(cols[0].1, Ok(vec![30f64.to_bits(), 40.5f64.to_bits()]));
    // Text cannot go to .npy.
    let out = polbrdf(&[
        "eval",
        "--material",
        "paint",
        "--input",
        d.join("g.feather").to_str().unwrap(),
        "--output",
        d.join("o.npy").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(3));
    let msg = stderr(&out);
    assert!(
        msg.contains("g.feather:1:") && msg.contains("`name`") && msg.contains("numbers only"),
        "{msg}"
    );
    assert!(!d.join("o.npy").exists());
}

#[test]
fn an_empty_table_gives_an_empty_table_with_the_schema() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let e = |_: ()| -> ArrayRef { Arc::new(Float64Array::from(Vec::<f64>::new())) };
    let bytes = arrow_bytes(
        &[
            ("theta_i_deg", e(())),
            ("phi_i_deg", e(())),
            ("theta_r_deg", e(())),
            ("phi_r_deg", e(())),
            ("label", Arc::new(StringArray::from(Vec::<String>::new()))),
        ],
        false,
        10,
    );
    std::fs::write(d.join("g.arrow"), bytes).unwrap();
    eval(&d.join("g.arrow"), &d.join("o.arrow"));
    let cols = read_arrow(&d.join("o.arrow"));
    assert_eq!(cols.len(), 5 + 19);
    assert_eq!(cols[4], ("label".into(), Err(vec![])));
}

#[test]
fn arrow_output_to_a_pipe_and_an_error_leaves_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("g.csv"),
        "theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n30,0,30,180\n",
    )
    .unwrap();
    // Standard output through a link named .arrow: the file format, append only.
    std::os::unix::fs::symlink("/dev/stdout", d.join("pipe.arrow")).unwrap();
    let out = polbrdf(&[
        "eval",
        "--material",
        "paint",
        "--input",
        d.join("g.csv").to_str().unwrap(),
        "--output",
        d.join("pipe.arrow").to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let r = arrow_ipc::reader::FileReader::try_new(std::io::Cursor::new(out.stdout), None).unwrap();
    assert_eq!(r.schema().fields().len(), 4 + 19);
    assert_eq!(r.map(|b| b.unwrap().num_rows()).sum::<usize>(), 1);
    // A null in row 2 of the second batch: an error naming row 3, nothing written.
    let bytes = arrow_bytes(
        &[
            (
                "theta_i_deg",
                Arc::new(Float64Array::from(vec![Some(30.0), Some(30.0), None])),
            ),
            (
                "phi_i_deg",
                Arc::new(Float64Array::from(vec![0.0, 0.0, 0.0])),
            ),
            (
                "theta_r_deg",
                Arc::new(Float64Array::from(vec![30.0, 30.0, 30.0])),
            ),
            (
                "phi_r_deg",
                Arc::new(Float64Array::from(vec![180.0, 180.0, 180.0])),
            ),
        ],
        false,
        2,
    );
    std::fs::write(d.join("n.arrow"), bytes).unwrap();
    let out = polbrdf(&[
        "eval",
        "--material",
        "paint",
        "--input",
        d.join("n.arrow").to_str().unwrap(),
        "--output",
        d.join("o.arrow").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(3));
    let msg = stderr(&out);
    assert!(
        msg.contains("n.arrow:3:") && msg.contains("`theta_i_deg`") && msg.contains("null"),
        "{msg}"
    );
    assert!(!d.join("o.arrow").exists());
    let left: Vec<_> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left.len(), 3, "{left:?}");
}
