//! The pipeline's validation of large patterns (a grid instead of a hash) reports exactly what
//! `Pattern::validate` reports: the same first duplicate, its nearest earlier point, the same
//! distance, and range errors first.

use tpi_core::benchmark::random_pattern;
use tpi_core::validate_pattern;
use tpi_core::Pattern;

#[test]
fn large_pattern_errors_match_the_pattern_check() {
    let base = random_pattern(20_000);
    assert!(validate_pattern(&base).is_ok());
    // Duplicates at various places, some with ties and several candidates.
    let mut cases: Vec<Vec<[f64; 2]>> = Vec::new();
    for (later, earlier, offset) in [
        (19_999, 3, 0.0),
        (12_000, 11_999, 4e-10),
        (5_000, 17_000, 9e-10),
        (7_000, 10, 1.1e-9),
    ] {
        let mut p = base.clone();
        p[later] = [base[earlier][0] + offset, base[earlier][1]];
        cases.push(p);
    }
    let mut tie = base.clone();
    tie[9_000] = [0.5, 0.5];
    tie[9_001] = [0.5 + 5e-10, 0.5];
    tie[9_002] = [0.5 - 5e-10, 0.5];
    cases.push(tie);
    let mut range = base.clone();
    range[15_000] = [1.0 + 1e-12, 0.3];
    range[16_000] = range[2];
    cases.push(range);
    let mut nan = base.clone();
    nan[100] = [f64::NAN, 0.5];
    cases.push(nan);
    let mut edge = base.clone();
    edge[42] = [1.0, 1.0];
    edge[43] = [1.0, 1.0 - 2e-10];
    cases.push(edge);
    for (k, p) in cases.iter().enumerate() {
        let expected = Pattern::new(p.clone())
            .validate()
            .err()
            .map(|e| e.to_string());
        let got = validate_pattern(p).err().map(|e| e.to_string());
        assert_eq!(got, expected, "case {k}");
    }
}
