//! Tests of `expr.rs`.

use super::eval::*;
use super::expr::*;
use std::collections::HashMap;

struct Store(HashMap<u32, f64>, HashMap<String, f64>);

impl Parameters for Store {
    fn numbered(&self, n: u32) -> Result<Option<f64>, String> {
        Ok(self.0.get(&n).copied())
    }
    fn named(&self, name: &str) -> Option<f64> {
        self.1.get(name).copied()
    }
}

fn store() -> Store {
    Store(HashMap::from([(1, 3.0), (2, 1.0), (3, 4.0)]), HashMap::from([("DEPTH".to_string(), -2.5)]))
}

fn eval(text: &str) -> Result<Option<f64>, String> {
    let mut c = Cursor::new(text.as_bytes(), 0);
    let e = c.real_value().map_err(|e| e.reason)?;
    assert_eq!(c.i, text.len(), "{text} read to the end");
    evaluate(&e, &store())
}

fn value(text: &str) -> f64 {
    eval(text).unwrap_or_else(|e| panic!("{text}: {e}")).unwrap()
}

#[test]
fn the_issue_example_and_precedence_read_as_linuxcnc_reads_them() {
    assert!((value("[#1*2+SIN[30]]") - 6.5).abs() < 1e-12);
    assert!((value("[2+3*4**2]") - 50.0).abs() < 1e-12);
    assert!((value("[10-4-3]") - 3.0).abs() < 1e-12);
    assert!((value("[1+2EQ3]") - 1.0).abs() < 1e-12);
    assert!((value("[1LT2AND3GT2]") - 1.0).abs() < 1e-12);
    assert!((value("-[#3]") + 4.0).abs() < 1e-12);
    assert!((value("[2*-#2]") + 2.0).abs() < 1e-12);
}

#[test]
fn parameters_can_be_indirect_computed_or_named() {
    assert!((value("##2") - 3.0).abs() < 1e-12);
    assert!((value("#[#2+2]") - 4.0).abs() < 1e-12);
    assert!((value("[#<DEPTH>*2]") + 5.0).abs() < 1e-12);
    assert!((value("EXISTS[#<DEPTH>]") - 1.0).abs() < 1e-12);
    assert!((value("EXISTS[#<NONE>]")).abs() < 1e-12);
    assert_eq!(eval("#9"), Ok(None));
    assert!(eval("#<NONE>").unwrap_err().contains("#<none> is not defined"));
}

#[test]
fn functions_take_degrees_and_both_atan_forms() {
    assert!((value("COS[60]") - 0.5).abs() < 1e-12);
    assert!((value("ATAN[1]/[1]") - 45.0).abs() < 1e-12);
    assert!((value("ATAN[1,-1]") - 135.0).abs() < 1e-12);
    assert!((value("POW[2,10]") - 1024.0).abs() < 1e-12);
    assert!((value("[FIX[-1.5]+FUP[1.2]+ROUND[2.5]+ABS[-1]]") - 4.0).abs() < 1e-12);
    assert!((value("[-7MOD3]") - 2.0).abs() < 1e-12);
    assert!((value("SQRT[16]") - 4.0).abs() < 1e-12);
}

#[test]
fn vacant_values_count_as_zero_but_compare_as_vacant() {
    assert!((value("[#9+1]") - 1.0).abs() < 1e-12);
    assert!((value("[#9EQ#8]") - 1.0).abs() < 1e-12);
    assert!((value("[#9EQ0]")).abs() < 1e-12);
    assert!((value("[#9NE0]") - 1.0).abs() < 1e-12);
}

#[test]
fn faults_name_their_reason() {
    assert!(eval("[1/0]").unwrap_err().contains("division by zero"));
    assert!(eval("SQRT[-1]").unwrap_err().contains("square root"));
    assert!(eval("ACOS[2]").unwrap_err().contains("domain"));
    assert!(eval("FOO[1]").unwrap_err().contains("FOO is not a function"));
    assert!(eval("[1+2").unwrap_err().contains("not closed"));
    assert!(eval("#1.5").unwrap_err().contains("whole number"));
    assert!((value("ATAN[1]") - 45.0).abs() < 1e-12);
    let deep = format!("{}1{}", "[".repeat(100), "]".repeat(100));
    assert!(eval(&deep).unwrap_err().contains("nest"));
}
