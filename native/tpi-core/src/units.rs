//! Length units of a model: read from the surface file's optional `"units"` field (Rhino's unit
//! systems, short or long names, see [`Units::from_name`]), carried by the surface
//! ([`crate::Surface::units`]) to the discretisation and every output, and used by the
//! fabrication writers (DXF `$INSUNITS`, G-code G20 / G21).
//!
//! tpi never rescales: the units only say what the model's lengths mean. A surface without
//! `"units"` is unitless (`Option<Units>::None`), and the outputs say so.

use std::fmt;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// Length units of the model (Rhino's length unit systems from microns to miles).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Units {
    /// Microns, micrometres (`um`; `$INSUNITS` 13).
    Microns,
    /// Millimetres (`mm`; `$INSUNITS` 4).
    Millimetres,
    /// Centimetres (`cm`; `$INSUNITS` 5).
    Centimetres,
    /// Metres (`m`; `$INSUNITS` 6). Default value (of the fabrication options).
    #[default]
    Metres,
    /// Kilometres (`km`; `$INSUNITS` 7).
    Kilometres,
    /// Inches (`in`; `$INSUNITS` 1).
    Inches,
    /// Feet (`ft`; `$INSUNITS` 2).
    Feet,
    /// Yards (`yd`; `$INSUNITS` 10).
    Yards,
    /// Miles (`mi`; `$INSUNITS` 3).
    Miles,
}

/// A units name that is none of the accepted ones; its message lists them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownUnits {
    /// The name as given.
    pub found: String,
}

impl fmt::Display for UnknownUnits {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "unknown units `{}`: expected one of {} (or the long names {}, as Rhino writes them; any case)",
            crate::error::bounded(&self.found, crate::error::QUOTE_LIMIT),
            Units::ALL
                .iter()
                .map(|u| format!("`{}`", u.short_name()))
                .collect::<Vec<_>>()
                .join(", "),
            Units::ALL
                .iter()
                .map(|u| format!("`{}`", u.rhino_name()))
                .collect::<Vec<_>>()
                .join(", "),
        )
    }
}

impl std::error::Error for UnknownUnits {}

impl Units {
    /// Every unit system, smallest first.
    pub const ALL: [Units; 9] = [
        Units::Microns,
        Units::Millimetres,
        Units::Centimetres,
        Units::Metres,
        Units::Kilometres,
        Units::Inches,
        Units::Feet,
        Units::Yards,
        Units::Miles,
    ];

    /// The short name, as written to every output: `um`, `mm`, `cm`, `m`, `km`, `in`, `ft`,
    /// `yd` or `mi`.
    pub fn short_name(self) -> &'static str {
        match self {
            Units::Microns => "um",
            Units::Millimetres => "mm",
            Units::Centimetres => "cm",
            Units::Metres => "m",
            Units::Kilometres => "km",
            Units::Inches => "in",
            Units::Feet => "ft",
            Units::Yards => "yd",
            Units::Miles => "mi",
        }
    }

    /// The name of Rhino's `UnitSystem` member (`Millimeters`, ...), as rhino3dm writes it.
    pub fn rhino_name(self) -> &'static str {
        match self {
            Units::Microns => "Microns",
            Units::Millimetres => "Millimeters",
            Units::Centimetres => "Centimeters",
            Units::Metres => "Meters",
            Units::Kilometres => "Kilometers",
            Units::Inches => "Inches",
            Units::Feet => "Feet",
            Units::Yards => "Yards",
            Units::Miles => "Miles",
        }
    }

    /// Reads a units name, case-insensitively: the short names of [`Units::short_name`], Rhino's
    /// names of [`Units::rhino_name`], and the British spellings (`millimetres`, ...) and
    /// `micrometers` / `micrometres`. Surrounding white space is ignored.
    pub fn from_name(name: &str) -> Result<Units, UnknownUnits> {
        let lower = name.trim().to_ascii_lowercase();
        let found = Units::ALL.into_iter().find(|u| {
            lower == u.short_name()
                || lower == u.rhino_name().to_ascii_lowercase()
                || lower == u.rhino_name().to_ascii_lowercase().replace("ers", "res")
        });
        match (found, lower.as_str()) {
            (Some(u), _) => Ok(u),
            (None, "micrometers" | "micrometres" | "micron") => Ok(Units::Microns),
            _ => Err(UnknownUnits {
                found: name.to_string(),
            }),
        }
    }

    /// Parses a units name ([`Units::from_name`]), `None` if unknown.
    pub fn parse(s: &str) -> Option<Units> {
        Units::from_name(s).ok()
    }

    /// DXF `$INSUNITS` code.
    pub fn insunits(self) -> u8 {
        match self {
            Units::Inches => 1,
            Units::Feet => 2,
            Units::Miles => 3,
            Units::Millimetres => 4,
            Units::Centimetres => 5,
            Units::Metres => 6,
            Units::Kilometres => 7,
            Units::Yards => 10,
            Units::Microns => 13,
        }
    }

    /// Length of one unit in millimetres.
    pub fn millimetres(self) -> f64 {
        match self {
            Units::Microns => 0.001,
            Units::Millimetres => 1.0,
            Units::Centimetres => 10.0,
            Units::Metres => 1000.0,
            Units::Kilometres => 1.0e6,
            Units::Inches => 25.4,
            Units::Feet => 304.8,
            Units::Yards => 914.4,
            Units::Miles => 1_609_344.0,
        }
    }
}

impl fmt::Display for Units {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.short_name())
    }
}

impl std::str::FromStr for Units {
    type Err = UnknownUnits;

    fn from_str(s: &str) -> Result<Units, UnknownUnits> {
        Units::from_name(s)
    }
}

impl Serialize for Units {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.short_name())
    }
}

impl<'de> Deserialize<'de> for Units {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Units, D::Error> {
        let name = String::deserialize(deserializer)?;
        Units::from_name(&name).map_err(serde::de::Error::custom)
    }
}

/// How outputs name optional units: the short name, or `unitless`.
pub fn units_label(units: Option<Units>) -> &'static str {
    units.map_or("unitless", Units::short_name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_reads_back() {
        for u in Units::ALL {
            assert_eq!(Units::from_name(u.short_name()), Ok(u));
            assert_eq!(Units::from_name(u.rhino_name()), Ok(u));
            assert_eq!(Units::from_name(&u.rhino_name().to_uppercase()), Ok(u));
        }
        assert_eq!(Units::from_name("Millimetres"), Ok(Units::Millimetres));
        assert_eq!(Units::from_name(" metres "), Ok(Units::Metres));
        assert_eq!(Units::from_name("micrometers"), Ok(Units::Microns));
        let e = Units::from_name("furlongs").unwrap_err();
        let message = e.to_string();
        assert!(message.contains("`furlongs`"), "{message}");
        for u in Units::ALL {
            assert!(
                message.contains(&format!("`{}`", u.short_name())),
                "{message}"
            );
        }
    }
}
