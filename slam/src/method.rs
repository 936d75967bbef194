//! The localisation methods `rusoar slam --method` runs and compares.

use std::str::FromStr;

/// A localisation method of `--method`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Method {
    /// Dead reckoning: the moving rules alone, the believed pose is the odometry.
    Dr,
    /// The thesis's SLAM rules (`rules/`).
    Thesis,
    /// Rules v2 (`rules/v2/`).
    V2,
    /// The EKF over the dead-reckoning runs' odometry and walls (`slam/src/ekf/`).
    Ekf,
    /// Rules v2 against the true map (`rules/v2/oracle.soar`).
    Oracle,
}

impl Method {
    /// The names `--method` takes, in the order the table lists them.
    pub const NAMES: [&'static str; 5] = ["dr", "thesis", "v2", "ekf", "oracle"];

    /// The name on the command line and in file names.
    pub fn name(self) -> &'static str {
        match self {
            Method::Dr => "dr",
            Method::Thesis => "thesis",
            Method::V2 => "v2",
            Method::Ekf => "ekf",
            Method::Oracle => "oracle",
        }
    }

    /// The name in tables and legends.
    pub fn label(self) -> &'static str {
        match self {
            Method::Dr => "dead reckoning",
            Method::Thesis => "thesis rules",
            Method::V2 => "rules v2",
            Method::Ekf => "EKF",
            Method::Oracle => "oracle (true map)",
        }
    }
}

impl FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "dr" => Ok(Method::Dr),
            "thesis" => Ok(Method::Thesis),
            "v2" => Ok(Method::V2),
            "ekf" => Ok(Method::Ekf),
            "oracle" => Ok(Method::Oracle),
            _ => Err(format!(
                "unknown method `{s}` (expected one of: {})",
                Method::NAMES.join(", ")
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn method_names_round_trip() {
        for n in Method::NAMES {
            assert_eq!(n.parse::<Method>().map(Method::name), Ok(n));
        }
        assert!("kalman".parse::<Method>().unwrap_err().contains("oracle"));
    }
}
