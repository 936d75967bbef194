//! Step 4b of the pipeline: wall extraction, from zone centres to Wall elements.
//!
//! Thesis, "Hough-Transform Java / Extracting Wall" (Figures 21 and 22): each zone's middle
//! gives a line (r, θ); "the very last thing to be done is find the beginning and ending points
//! for all lines", then pack them with the robot's position and the time of creation into Wall
//! elements.
//!
//! Here, with the zones of [`super::zones::find_zones`]:
//! 1. **Candidates**: the zones' centres, strongest first.
//! 2. **Supporting returns** of a candidate line: in `points` mode the returns within
//!    `support_mm` of it; in `arcs` mode the returns facing it (its normal inside their beam
//!    cone) whose visible arc touches it within `support_mm`, taken at their contact point.
//! 3. **Refinement** (`refine`, on by default): the line is refitted to its support (see the
//!    `fit` module), which removes the bin quantisation of the zone centre.
//! 4. **Start and end**: the supporting returns are sorted along the line and split wherever
//!    two neighbours are more than `gap_mm` apart (two walls on one line, e.g. either side of a
//!    doorway). A piece becomes a wall when it has at least `min_points` returns **not already
//!    used** by a stronger wall (so a peak's neighbouring cells and its mirror image near r = 0
//!    add nothing) and is at least `min_length_mm` long; it runs from its first to its last
//!    return projected on the line. Returns already used may still extend a piece, so that both
//!    walls of a corner reach the corner.
//! 5. **Free space**: a piece is dropped when more than half as many returns saw through it as
//!    support it (their beam axis crosses it, at most 60° from its normal, and their echo comes
//!    from more than `support_mm` beyond it: a wall there would have answered first).
//! 6. **Merging**: a piece on the same line as a wall already extracted (within `support_mm`
//!    and 3°) and overlapping it or within `gap_mm` of it joins that wall.

use super::convert::SonarPoint;
use super::fit::{angle_diff, robust_fit, tangent_fit, Line, Ray, MAX_TURN_DEG};
use super::settings::VoteMode;
use super::wall::{RefPose, Wall};
use super::zones::{Peak, Zone};
use super::Settings;

/// Most line candidates examined in one extraction (strongest first); only a very low k
/// produces more.
const MAX_CANDIDATES: usize = 256;

/// A line with the extent of its supporting returns, from `t0` to `t1` along it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Segment {
    line: Line,
    t0: f64,
    t1: f64,
}

/// A wall being built: its segment and the returns it is made of.
struct Draft {
    seg: Segment,
    members: Vec<usize>,
}

/// Width of the beam-direction buckets used to find the returns that may face a line, degrees.
const BUCKET_DEG: f64 = 10.0;
/// Beams crossing a wall further than this from its normal, degrees, are not counted as seeing
/// through it (a real sonar loses such echoes by specular reflection).
const MAX_CROSSING_DEG: f64 = 60.0;

/// Number of beam-direction buckets.
const N_BUCKETS: usize = (360.0 / BUCKET_DEG) as usize;

/// The wall extractor over one set of filtered returns.
struct Extractor<'a> {
    rays: Vec<Ray>,
    /// Which rays fall in each beam-direction bucket of [`BUCKET_DEG`] (arcs mode): bit `i % 64`
    /// of word `b * words + i / 64` is set when ray `i` is in bucket `b`.
    buckets: Vec<u64>,
    /// Words per bucket.
    words: usize,
    settings: &'a Settings,
    cos_half: f64,
    floor: f64,
}

impl<'a> Extractor<'a> {
    fn new(points: &[SonarPoint], settings: &'a Settings) -> Self {
        let words = points.len().div_ceil(64);
        let mut buckets = vec![0u64; N_BUCKETS * words];
        for (i, p) in points.iter().enumerate() {
            let b = (p.heading.to_degrees().rem_euclid(360.0) / BUCKET_DEG) as usize;
            buckets[b.min(N_BUCKETS - 1) * words + i / 64] |= 1 << (i % 64);
        }
        Extractor {
            rays: points.iter().map(Ray::from).collect(),
            buckets,
            words,
            settings,
            cos_half: (settings.beam_deg.to_radians() / 2.0).cos(),
            floor: settings.r_bin_mm / 2.0,
        }
    }

    /// Indices of the returns that may support `line`, in increasing order: all of them in
    /// points mode; in arcs mode only those whose beam points within the cone of the line's
    /// normal (either way).
    fn may_support(&self, line: &Line) -> Vec<usize> {
        if self.settings.vote_mode == VoteMode::Points || self.settings.beam_deg >= 180.0 {
            return (0..self.rays.len()).collect();
        }
        let n = N_BUCKETS as i64;
        let half = self.settings.beam_deg / 2.0;
        let mut wanted = [false; N_BUCKETS];
        for centre in [line.th.to_degrees(), line.th.to_degrees() + 180.0] {
            let lo = ((centre - half) / BUCKET_DEG).floor() as i64;
            let hi = ((centre + half) / BUCKET_DEG).floor() as i64;
            for b in lo..=hi.min(lo + n - 1) {
                wanted[b.rem_euclid(n) as usize] = true;
            }
        }
        let mut list = [0usize; N_BUCKETS];
        let mut count = 0;
        for (b, _) in wanted.iter().enumerate().filter(|(_, &on)| on) {
            list[count] = b * self.words;
            count += 1;
        }
        // The union of the wanted buckets' rays, read off their bit sets word by word.
        let mut out = Vec::new();
        for w in 0..self.words {
            let bits_of = |start: &usize| self.buckets[start + w];
            let mut bits = list[..count].iter().map(bits_of).fold(0, |a, b| a | b);
            while bits != 0 {
                out.push(w * 64 + bits.trailing_zeros() as usize);
                bits &= bits - 1;
            }
        }
        out
    }

    /// Where ray `p` supports `line`, or `None` if it does not.
    fn support_at(&self, p: &Ray, line: &Line) -> Option<(f64, f64)> {
        match self.settings.vote_mode {
            VoteMode::Points => {
                (line.distance(p.x, p.y).abs() <= self.settings.support_mm).then_some((p.x, p.y))
            }
            VoteMode::Arcs => {
                let sign = p.facing(line, self.cos_half)?;
                let d = p.tangent_r(sign, line) - line.r;
                (d.abs() <= self.settings.support_mm).then(|| p.contact(sign, line))
            }
        }
    }

    /// The supporting returns of `line` among `of`, with their positions along it.
    fn support(&self, of: impl Iterator<Item = usize>, line: &Line) -> Vec<(usize, f64)> {
        of.filter_map(|i| {
            self.support_at(&self.rays[i], line)
                .map(|(x, y)| (i, line.along(x, y)))
        })
        .collect()
    }

    /// The line refitted to `members`, starting from `line`.
    fn refit(&self, members: &[usize], line: &Line) -> Line {
        if !self.settings.refine {
            return *line;
        }
        let rays: Vec<Ray> = members.iter().map(|&i| self.rays[i]).collect();
        let start = match self.settings.vote_mode {
            VoteMode::Points => {
                let xy: Vec<(f64, f64)> = rays.iter().map(|p| (p.x, p.y)).collect();
                let (r, th) = robust_fit(&xy, line.r, line.th, self.floor);
                Line::new(r, th)
            }
            VoteMode::Arcs => *line,
        };
        tangent_fit(&rays, &start, self.cos_half, self.floor)
            .unwrap_or(start)
            .normalised()
    }

    /// The segment of `members` near `line`: refitted line and extent; `None` if shorter than
    /// `min_length_mm` or unsupported.
    fn segment(&self, members: &[usize], line: &Line) -> Option<Segment> {
        let line = self.refit(members, line);
        let along = self.support(members.iter().copied(), &line);
        let t0 = along.iter().map(|a| a.1).fold(f64::INFINITY, f64::min);
        let t1 = along.iter().map(|a| a.1).fold(f64::NEG_INFINITY, f64::max);
        (t1 - t0 >= self.settings.min_length_mm).then_some(Segment { line, t0, t1 })
    }

    /// The returns that saw through `seg`: their beam axis crosses it (at no more than
    /// [`MAX_CROSSING_DEG`] from its normal) and they report an echo more than `support_mm`
    /// beyond it. A wall there would have answered first.
    fn see_through(&self, seg: &Segment) -> usize {
        let (a, b) = (seg.line.point(seg.t0), seg.line.point(seg.t1));
        let (ex, ey) = (b.0 - a.0, b.1 - a.1);
        let cos_min = MAX_CROSSING_DEG.to_radians().cos();
        self.rays
            .iter()
            .filter(|p| {
                let denom = p.hx * ey - p.hy * ex;
                let len = ex.hypot(ey);
                if len == 0.0 || denom.abs() < cos_min * len {
                    return false;
                }
                let (wx, wy) = (a.0 - p.sx, a.1 - p.sy);
                let t = (wx * ey - wy * ex) / denom;
                let u = (wx * p.hy - wy * p.hx) / denom;
                t >= 0.0 && (0.0..=1.0).contains(&u) && t + self.settings.support_mm < p.range
            })
            .count()
    }

    /// Whether `b` lies on `a`'s line and overlaps it or comes within `gap_mm` of it.
    fn joins(&self, a: &Segment, b: &Segment) -> bool {
        let limit = MAX_TURN_DEG.to_radians();
        let (la, lb) = (&a.line, &b.line);
        let same = (angle_diff(la.th, lb.th).abs() <= limit
            && (la.r - lb.r).abs() <= self.settings.support_mm)
            || (angle_diff(la.th, lb.th + std::f64::consts::PI).abs() <= limit
                && (la.r + lb.r).abs() <= self.settings.support_mm);
        if !same {
            return false;
        }
        let ((x0, y0), (x1, y1)) = (lb.point(b.t0), lb.point(b.t1));
        let (u, v) = (la.along(x0, y0), la.along(x1, y1));
        let (b0, b1) = (u.min(v), u.max(v));
        b0 <= a.t1 + self.settings.gap_mm && a.t0 <= b1 + self.settings.gap_mm
    }

    fn run(&self, zones: &[Zone]) -> Vec<Segment> {
        let mut candidates: Vec<&Peak> = zones.iter().flat_map(|z| z.peaks.iter()).collect();
        candidates.sort_by(|a, b| b.votes.cmp(&a.votes).then((a.t, a.ri).cmp(&(b.t, b.ri))));
        candidates.truncate(MAX_CANDIDATES);
        let min_points = self.settings.min_points.max(2);
        let mut used = vec![false; self.rays.len()];
        let mut drafts: Vec<Draft> = Vec::new();
        for peak in candidates {
            let mut line = Line::new(peak.r_mm, peak.theta_deg.to_radians()).normalised();
            let mut along = self.support(self.may_support(&line).into_iter(), &line);
            if along.iter().filter(|a| !used[a.0]).count() < min_points {
                continue;
            }
            if self.settings.refine {
                let members: Vec<usize> = along.iter().map(|a| a.0).collect();
                line = self.refit(&members, &line);
                along = self.support(self.may_support(&line).into_iter(), &line);
            }
            along.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
            let mut runs: Vec<Vec<(usize, f64)>> = Vec::new();
            for a in along {
                match runs.last_mut() {
                    Some(run)
                        if run
                            .last()
                            .is_some_and(|l| a.1 - l.1 <= self.settings.gap_mm) =>
                    {
                        run.push(a)
                    }
                    _ => runs.push(vec![a]),
                }
            }
            for run in runs {
                if run.iter().filter(|a| !used[a.0]).count() < min_points {
                    continue;
                }
                let members: Vec<usize> = run.iter().map(|a| a.0).collect();
                let Some(seg) = self.segment(&members, &line) else {
                    continue;
                };
                if 2 * self.see_through(&seg) > members.len() {
                    continue;
                }
                for &i in &members {
                    used[i] = true;
                }
                match drafts.iter_mut().find(|d| self.joins(&d.seg, &seg)) {
                    Some(d) => {
                        d.members.extend(members);
                        d.members.sort_unstable();
                        d.members.dedup();
                        if let Some(merged) = self.segment(&d.members, &d.seg.line) {
                            d.seg = merged;
                        }
                    }
                    None => drafts.push(Draft { seg, members }),
                }
            }
        }
        drafts.into_iter().map(|d| d.seg).collect()
    }
}

/// Extracts walls from the filtered returns `points` and the zones of their Hough space.
/// `reference` is the robot's pose for `^Ref` and `time` the `^Time` stamp.
pub fn extract_walls(
    points: &[SonarPoint],
    zones: &[Zone],
    settings: &Settings,
    reference: RefPose,
    time: i64,
) -> Vec<Wall> {
    Extractor::new(points, settings)
        .run(zones)
        .into_iter()
        .map(|seg| {
            Wall::new(
                seg.line.r,
                seg.line.th.to_degrees(),
                seg.line.point(seg.t0),
                seg.line.point(seg.t1),
                reference,
                time,
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::super::hough;
    use super::super::wall::PointMm;
    use super::super::zones::find_zones;
    use super::*;

    /// A return lying on a wall at `(x, y)` whose normal, pointing away from the transducer, is
    /// `n` (unit): the transducer sits 1 m back along the normal, looking at the wall head-on,
    /// and `ripple` mm of range noise moves the return along the normal.
    fn on_wall(x: f64, y: f64, n: (f64, f64), ripple: f64) -> SonarPoint {
        SonarPoint {
            x: x + ripple * n.0,
            y: y + ripple * n.1,
            sensor_x: x - 1000.0 * n.0,
            sensor_y: y - 1000.0 * n.1,
            heading: n.1.atan2(n.0),
            range: 1000.0 + ripple,
        }
    }

    /// Returns every `step` mm from (x1, y1) to (x2, y2), seen from the origin's side, with the
    /// ripple `noise(i)` on the i-th.
    fn wall(
        x1: f64,
        y1: f64,
        x2: f64,
        y2: f64,
        step: f64,
        noise: impl Fn(usize) -> f64,
    ) -> Vec<SonarPoint> {
        let len = (x2 - x1).hypot(y2 - y1);
        let (mut nx, mut ny) = ((y2 - y1) / len, -(x2 - x1) / len);
        if nx * x1 + ny * y1 < 0.0 {
            (nx, ny) = (-nx, -ny);
        }
        let n = (len / step).round() as usize;
        (0..=n)
            .map(|i| {
                let f = i as f64 / n as f64;
                on_wall(x1 + f * (x2 - x1), y1 + f * (y2 - y1), (nx, ny), noise(i))
            })
            .collect()
    }

    fn clean(x1: f64, y1: f64, x2: f64, y2: f64) -> Vec<SonarPoint> {
        wall(x1, y1, x2, y2, 50.0, |_| 0.0)
    }

    fn run(points: &[SonarPoint], settings: &Settings) -> Vec<Wall> {
        let acc = hough::hough(points, settings);
        let zones = find_zones(&acc, settings.k);
        extract_walls(points, &zones, settings, RefPose::default(), 7)
    }

    fn settings(mode: VoteMode) -> Settings {
        Settings {
            vote_mode: mode,
            ..Settings::default()
        }
    }

    /// A 4 × 4 m room centred on the origin, returns every 40 mm with a ±15 mm deterministic
    /// ripple (sonar range noise).
    fn square_room() -> Vec<SonarPoint> {
        let mut pts = Vec::new();
        for (x1, y1, x2, y2) in [
            (-2000.0, -2000.0, 2000.0, -2000.0),
            (2000.0, -2000.0, 2000.0, 2000.0),
            (2000.0, 2000.0, -2000.0, 2000.0),
            (-2000.0, 2000.0, -2000.0, -2000.0),
        ] {
            pts.extend(wall(x1, y1, x2, y2, 40.0, |i| {
                15.0 * ((i * 7919) % 13) as f64 / 6.0 - 15.0
            }));
        }
        pts
    }

    #[test]
    fn square_room_walls_within_2cm_and_1deg() {
        for mode in [VoteMode::Points, VoteMode::Arcs] {
            let walls = run(&square_room(), &settings(mode));
            assert_eq!(walls.len(), 4, "{mode}: {walls:#?}");
            let mut worst = (0.0f64, 0.0f64, 0.0f64);
            for th in [0.0, 90.0, 180.0, 270.0] {
                let w = walls
                    .iter()
                    .find(|w| angle_diff(w.line.1.to_radians(), f64::to_radians(th)).abs() < 0.1)
                    .expect("wall found");
                let dr = (w.line.0 - 2000.0).abs();
                let dth = angle_diff(w.line.1.to_radians(), f64::to_radians(th))
                    .to_degrees()
                    .abs();
                worst = (
                    worst.0.max(dr),
                    worst.1.max(dth),
                    worst.2.max((w.length - 4000.0).abs()),
                );
                assert!(dr < 20.0, "{mode}: r {} vs 2000", w.line.0);
                assert!(dth < 1.0, "{mode}: θ {} vs {th}", w.line.1);
                assert!((w.r - 2000).abs() < 20, "R {}", w.r);
                assert_eq!(w.th, th as i64);
                assert!(
                    (w.length - 4000.0).abs() < 60.0,
                    "{mode}: length {}",
                    w.length
                );
                assert_eq!(w.time, 7);
            }
            eprintln!(
                "square room ({mode}): worst Δr {:.2} mm, Δθ {:.3}°, Δlength {:.1} mm",
                worst.0, worst.1, worst.2
            );
        }
    }

    #[test]
    fn square_room_without_refinement_is_within_a_bin() {
        for mode in [VoteMode::Points, VoteMode::Arcs] {
            let settings = Settings {
                refine: false,
                ..settings(mode)
            };
            let walls = run(&square_room(), &settings);
            assert_eq!(walls.len(), 4, "{mode}");
            for w in &walls {
                assert!((w.line.0 - 2000.0).abs() <= 25.0, "{mode}: r {}", w.line.0);
                assert_eq!(w.th % 90, 0);
            }
        }
    }

    #[test]
    fn oblique_wall_and_start_end() {
        // A wall on r = 1800 at θ = 37°, from along-coordinate −1000 to +1500.
        let th = 37f64.to_radians();
        let (c, s) = (th.cos(), th.sin());
        let at = |t: f64| (1800.0 * c - t * s, 1800.0 * s + t * c);
        let (a, b) = (at(-1000.0), at(1500.0));
        for mode in [VoteMode::Points, VoteMode::Arcs] {
            let walls = run(&clean(a.0, a.1, b.0, b.1), &settings(mode));
            assert_eq!(walls.len(), 1, "{mode}");
            let w = &walls[0];
            assert!(
                (w.line.0 - 1800.0).abs() < 1.0 && (w.line.1 - 37.0).abs() < 0.06,
                "{mode}: {w:?}"
            );
            assert_eq!((w.r, w.th), (1800, 37));
            let close = |p: PointMm, q: (f64, f64)| {
                (p.x as f64 - q.0).abs() <= 3.0 && (p.y as f64 - q.1).abs() <= 3.0
            };
            assert!(close(w.start, a) && close(w.end, b), "{mode}: {w:?}");
            assert!((w.length - 2500.0).abs() < 3.0);
        }
    }

    #[test]
    fn gap_splits_collinear_walls() {
        // Two pieces of the line y = 1500 with a 1.2 m doorway between them.
        for mode in [VoteMode::Points, VoteMode::Arcs] {
            let mut pts = clean(-2500.0, 1500.0, -600.0, 1500.0);
            pts.extend(clean(600.0, 1500.0, 2500.0, 1500.0));
            let mut walls = run(&pts, &settings(mode));
            assert_eq!(walls.len(), 2, "{mode}: {walls:#?}");
            walls.sort_by_key(|w| w.start.x.min(w.end.x));
            assert!(walls.iter().all(|w| w.r == 1500 && w.th == 90));
            let xs: Vec<(i64, i64)> = walls
                .iter()
                .map(|w| (w.start.x.min(w.end.x), w.start.x.max(w.end.x)))
                .collect();
            assert_eq!(xs, vec![(-2500, -600), (600, 2500)], "{mode}");
        }
    }

    #[test]
    fn line_through_origin_is_found_once() {
        for mode in [VoteMode::Points, VoteMode::Arcs] {
            let walls = run(&clean(-2000.0, 0.0, 2000.0, 0.0), &settings(mode));
            assert_eq!(walls.len(), 1, "{mode}: {walls:#?}");
            assert_eq!(walls[0].r, 0);
            assert!(walls[0].th == 90 || walls[0].th == 270);
        }
    }

    #[test]
    fn scattered_noise_gives_no_walls() {
        // 60 pseudo-random returns in a 6 m square: no line gathers more than k votes.
        let mut state = 12345u64;
        let mut next = || crate::rng::splitmix64(&mut state);
        let pts: Vec<SonarPoint> = (0..60)
            .map(|_| {
                let (x, y) = (
                    (next() % 6000) as f64 - 3000.0,
                    (next() % 6000) as f64 - 3000.0,
                );
                let heading = (next() % 360) as f64;
                on_wall(
                    x,
                    y,
                    (heading.to_radians().cos(), heading.to_radians().sin()),
                    0.0,
                )
            })
            .collect();
        for mode in [VoteMode::Points, VoteMode::Arcs] {
            assert!(run(&pts, &settings(mode)).is_empty(), "{mode}");
        }
    }

    #[test]
    fn high_k_hides_weak_walls() {
        for mode in [VoteMode::Points, VoteMode::Arcs] {
            let mut pts = clean(-2000.0, 1000.0, 2000.0, 1000.0); // 81 returns
            pts.extend(clean(1500.0, -800.0, 1500.0, -50.0)); // 16 returns
            let with_k = |k| Settings {
                k,
                ..settings(mode)
            };
            assert_eq!(run(&pts, &with_k(12)).len(), 2, "{mode}");
            assert_eq!(run(&pts, &with_k(20)).len(), 1, "{mode}");
            assert_eq!(run(&pts, &with_k(81)).len(), 0, "{mode}");
        }
    }

    #[test]
    fn duplicate_pieces_merge() {
        // The same wall seen twice with a 30 mm offset in range (two passes of the robot): one
        // wall, not two.
        for mode in [VoteMode::Points, VoteMode::Arcs] {
            let mut pts = clean(-2000.0, 2000.0, 2000.0, 2000.0);
            pts.extend(wall(-2000.0, 2000.0, 2000.0, 2000.0, 50.0, |_| 60.0));
            let walls = run(&pts, &settings(mode));
            assert_eq!(walls.len(), 1, "{mode}: {walls:#?}");
            assert!(
                (walls[0].line.0 - 2030.0).abs() < 5.0,
                "{mode}: {:?}",
                walls[0].line
            );
        }
    }
}
