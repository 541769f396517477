//! Surface files: any text read as a surface record never panics; an error message is
//! bounded; a surface that builds evaluates to finite points inside its domain.
#![no_main]

use libfuzzer_sys::fuzz_target;
use tpi_core::{bound_message, Surface, SurfaceSpec, MESSAGE_LIMIT};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match SurfaceSpec::from_json(text, "fuzz.json") {
        Err(e) => {
            let message = bound_message(&e.to_string());
            assert!(message.chars().count() <= MESSAGE_LIMIT);
        }
        Ok(spec) => match spec.build() {
            Err(e) => assert!(e.to_string().len() < 4096, "{}", e.to_string().len()),
            Ok(model) => {
                let d = model.domain();
                for st in [[0.0, 0.0], [0.5, 0.5], [1.0, 1.0], [0.25, 0.75]] {
                    let [u, v] = d.from_normalised(st);
                    let p = model.point_at(u, v);
                    assert!(p.is_finite(), "{spec:?} at {st:?}: {p}");
                }
            }
        },
    }
});
