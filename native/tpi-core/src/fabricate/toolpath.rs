//! G-code for a 3-axis router (written in a later step).

/// Parameters of the G-code.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToolpathOptions {
    /// Tool diameter. Default value: 0.006.
    pub tool_diameter: f64,
}

impl Default for ToolpathOptions {
    fn default() -> Self {
        Self {
            tool_diameter: 0.006,
        }
    }
}
