//! An EKF SLAM baseline on the walls the Soar rules receive: the robot pose and (r, θ) wall
//! features in one state, predicted from the odometry the agent gets and updated from the
//! Hough pipeline's walls, with χ² gating.
//!
//! - [`line`]: the (r, θ) line, its two forms, robot/world conversions and their Jacobians;
//! - [`chi2`]: χ² quantiles for the gates and the NEES bounds;
//! - [`filter`]: the [`Ekf`] itself;
//! - [`replay`]: the filter run over a dead-reckoning run's odometry and walls, step by step;
//! - [`table`]: `ekf.md` and `ekf-runs.csv`, the EKF beside dead reckoning, paired by seed.

pub mod chi2;
pub mod filter;
pub mod line;
pub mod replay;
pub mod table;

pub use filter::{Association, Ekf, Noise};
pub use line::Line;
pub use replay::{replay, EkfRun, EkfStep};
