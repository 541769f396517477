//! Pattern files and generator specs: never a panic; a spec that passes the cheap
//! arithmetic check really gives at least 3 points that are not all collinear; an error
//! message is bounded.
#![no_main]

use libfuzzer_sys::fuzz_target;
use tpi_core::{Generator, Pattern, TpiError};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Err(e) = Pattern::from_json(text, "fuzz.json") {
        assert!(e.to_string().len() < 4096);
    }
    match Generator::parse(text) {
        Err(e) => assert!(e.to_string().len() < 4096, "{}", e.to_string().len()),
        Ok(generator) => {
            // Keep the runs short: big generators are checked by arithmetic only.
            let small = generator.expected_count().is_some_and(|n| n <= 20_000);
            let checked = generator.check_discretisable();
            if small {
                let pattern = generator.generate();
                match checked {
                    Ok(()) => match pattern.validate() {
                        Ok(()) | Err(TpiError::DuplicatePatternPoint { .. }) => {}
                        Err(e) => panic!("{generator}: passed the cheap check but {e}"),
                    },
                    Err(TpiError::TooFewPatternPoints { found, .. }) => {
                        assert_eq!(found, pattern.len())
                    }
                    Err(_) => {}
                }
            }
        }
    }
});
