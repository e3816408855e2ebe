//! Tests of `line.rs`.

use super::expr::Expr;
use super::line::*;

fn parse(text: &str) -> ParsedLine {
    parse_line(text.as_bytes())
}

fn letters(p: &ParsedLine) -> String {
    p.items
        .iter()
        .map(|s| match &s.item {
            Item::Word { letter, .. } => char::from(*letter).to_string(),
            Item::Assign { .. } => "=".to_string(),
            other => format!("{other:?}").split([' ', '{']).next().unwrap_or("").to_string(),
        })
        .collect::<Vec<_>>()
        .join(" ")
}

#[test]
fn words_with_expressions_keep_their_spans_in_the_original_line() {
    let p = parse("G1 X[#1*2+SIN[30]] y - 2 (c) F#<feed>");
    assert!(p.faults.is_empty(), "{:?}", p.faults);
    assert_eq!(letters(&p), "G X Y F");
    let x = &p.items[1];
    assert_eq!((x.start, x.end), (3, 18));
    let y = &p.items[2];
    assert_eq!((y.start, y.end), (19, 24));
}

#[test]
fn assignments_o_words_and_fanuc_statements_are_read() {
    assert_eq!(letters(&parse("#1 = 5 #<depth> = [#1 / 2] G0 X#1")), "= = G X");
    let p = parse("o100 repeat [#2 + 1]");
    assert!(
        matches!(&p.items[0].item, Item::OWord { name: OName::Number(100), keyword: OKeyword::Repeat, args } if args.len() == 1)
    );
    let p = parse("o<pocket> call [10] [2.5]");
    assert!(
        matches!(&p.items[0].item, Item::OWord { name: OName::Name(n), keyword: OKeyword::Call, args } if n == "POCKET" && args.len() == 2)
    );
    assert!(matches!(parse("O1000 (SUB)").items[0].item, Item::ProgramLabel { number: 1000 }));
    assert!(matches!(parse("N10 IF [#1 GT 3] GOTO 50").items[1].item, Item::If { then: Then::Goto(_), .. }));
    assert!(matches!(parse("IF [#1 EQ #0] THEN #1 = 2").items[0].item, Item::If { then: Then::Assign(_), .. }));
    assert!(matches!(parse("WHILE [#1 LT 10] DO 1").items[0].item, Item::While { id: 1, .. }));
    assert!(matches!(parse("END 1").items[0].item, Item::End { id: 1 }));
    assert!(matches!(parse("#1 = #1 + 1").items[0].item, Item::Assign { .. }));
}

#[test]
fn polar_words_and_blanks_inside_numbers_read_as_linuxcnc_reads_them() {
    let p = parse("G1 @.5 ^90 Z1 0");
    assert!(p.faults.is_empty(), "{:?}", p.faults);
    assert_eq!(letters(&p), "G @ ^ Z");
    assert!(matches!(p.items[3].item, Item::Word { value: Expr::Number(v), .. } if (v - 10.0).abs() < 1e-12));
}

#[test]
fn each_bad_word_is_one_fault_and_reading_goes_on() {
    let p = parse("G1 X$$5 Y[1+ Z2 Q");
    let reasons: Vec<&str> = p.faults.iter().map(|f| f.reason.as_str()).collect();
    assert_eq!(p.faults.len(), 3, "{reasons:?}");
    assert_eq!((p.faults[0].start, p.faults[0].end), (3, 7), "{reasons:?}");
    assert_eq!((p.faults[1].start, p.faults[1].end), (8, 12), "{reasons:?}");
    assert!(reasons[1].contains("expected a number"), "{reasons:?}");
    assert!(reasons[2].contains("followed by a number"), "{reasons:?}");
    assert_eq!(letters(&p), "G Z");
}

#[test]
fn a_control_statement_with_other_words_is_a_fault() {
    assert!(parse("o100 sub G1 X1").faults.iter().any(|f| f.reason.contains("alone")));
    assert!(parse("N20 o100 endsub").faults.is_empty());
    assert!(parse("o100").faults.iter().all(|f| !f.reason.is_empty()));
    assert!(matches!(parse("o100").items[0].item, Item::ProgramLabel { number: 100 }));
    assert!(parse("o100 foo").faults[0].reason.contains("keyword"));
}
