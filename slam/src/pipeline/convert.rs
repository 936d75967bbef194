//! Step 1 of the pipeline: the sonar data converter.
//!
//! Thesis, "Hough-Transform Java / Sonar Data Converter": the robot reports one distance per
//! transducer; "the converter will pair each sonar value with the angle of its transducer, then
//! convert those pairs into x,y coordinates on the image space" (Figures 14 and 15). Here each
//! range is placed along its transducer's beam axis, from the transducer's position (ARIA
//! geometry, `params/p2dx.p`), in the frame of the robot's **believed** pose, in mm. The sensor
//! position and beam direction are kept with each point because the noise filter draws the
//! return's visible arc from them.

use super::super::geom::{Point, Pose};
use super::super::sonar::Transducer;
use super::Settings;

/// One converted sonar return, in the believed frame, mm.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SonarPoint {
    /// Return position x, mm.
    pub x: f64,
    /// Return position y, mm.
    pub y: f64,
    /// Transducer position x, mm.
    pub sensor_x: f64,
    /// Transducer position y, mm.
    pub sensor_y: f64,
    /// Beam axis direction, radians.
    pub heading: f64,
    /// Measured range, mm.
    pub range: f64,
}

/// Converts one scan: `ranges_mm[i]` is the reading of `transducers[i]` taken at the believed
/// robot pose `pose`. Readings at or below `settings.min_range_mm`, at or beyond
/// `settings.max_range_mm` (no echo), or not finite are dropped.
pub fn convert(
    ranges_mm: &[f64],
    transducers: &[Transducer],
    pose: &Pose,
    settings: &Settings,
) -> Vec<SonarPoint> {
    let robot_mm = Pose::new(pose.x_mm(), pose.y_mm(), pose.th);
    ranges_mm
        .iter()
        .zip(transducers)
        .filter(|(r, _)| {
            r.is_finite() && **r > settings.min_range_mm && **r < settings.max_range_mm
        })
        .filter_map(|(&range, t)| {
            let sensor = robot_mm.transform(Point::new(t.x_mm, t.y_mm));
            let heading = pose.th + t.heading_deg.to_radians();
            let (s, c) = heading.sin_cos();
            let p = SonarPoint {
                x: sensor.x + range * c,
                y: sensor.y + range * s,
                sensor_x: sensor.x,
                sensor_y: sensor.y,
                heading,
                range,
            };
            (p.x.is_finite() && p.y.is_finite()).then_some(p)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::super::super::sonar::P2DX_SONARS;
    use super::*;

    #[test]
    fn at_origin_points_follow_transducers() {
        let ranges = [1000.0; 16];
        let pts = convert(
            &ranges,
            &P2DX_SONARS,
            &Pose::default(),
            &Settings::default(),
        );
        assert_eq!(pts.len(), 16);
        // Sonar 0: at (69, 136) looking +y → (69, 1136).
        assert!((pts[0].x - 69.0).abs() < 1e-9 && (pts[0].y - 1136.0).abs() < 1e-9);
        // Sonar 3: at (166, 27) looking 10°.
        let a = 10f64.to_radians();
        assert!((pts[3].x - (166.0 + 1000.0 * a.cos())).abs() < 1e-9);
        assert!((pts[3].y - (27.0 + 1000.0 * a.sin())).abs() < 1e-9);
        // Sonar 11: at (−255, −27) looking −170°.
        let a = (-170f64).to_radians();
        assert!((pts[11].x - (-255.0 + 1000.0 * a.cos())).abs() < 1e-9);
    }

    #[test]
    fn believed_pose_moves_and_turns_points() {
        // Robot believed at (2 m, 1 m) facing +y: sonar 3 (x 166, y 27 on the body) sits at
        // (2000 − 27, 1000 + 166), and its beam points at 100°.
        let mut ranges = [5000.0; 16];
        ranges[3] = 500.0;
        let pose = Pose::from_mm_deg(2000.0, 1000.0, 90.0);
        let pts = convert(&ranges, &P2DX_SONARS, &pose, &Settings::default());
        assert_eq!(pts.len(), 1, "max-range readings are dropped");
        let p = pts[0];
        assert!((p.sensor_x - 1973.0).abs() < 1e-9 && (p.sensor_y - 1166.0).abs() < 1e-9);
        let a = 100f64.to_radians();
        assert!((p.x - (1973.0 + 500.0 * a.cos())).abs() < 1e-9);
        assert!((p.y - (1166.0 + 500.0 * a.sin())).abs() < 1e-9);
        assert_eq!(p.range, 500.0);
    }

    #[test]
    fn bad_readings_are_dropped() {
        let ranges = [f64::NAN, 150.0, 149.0, 4900.0, f64::INFINITY, -3.0, 151.0];
        let pts = convert(
            &ranges,
            &P2DX_SONARS,
            &Pose::default(),
            &Settings::default(),
        );
        assert_eq!(pts.len(), 1);
        assert_eq!(pts[0].range, 151.0);
        let pose = Pose::new(f64::NAN, 0.0, 0.0);
        assert!(convert(&[1000.0], &P2DX_SONARS, &pose, &Settings::default()).is_empty());
    }
}
