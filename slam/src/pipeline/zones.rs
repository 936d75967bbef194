//! Step 4a of the pipeline: zones of the voted Hough space and their centres.
//!
//! Thesis, "Hough-Transform Java / Extracting Wall" (Figure 21): "the wall extractor will scan
//! through and locate zone(s) which the voting numbers are higher than critical point k", then
//! "find a single dot in the middle of each zone".
//!
//! - A zone is a connected group (8-neighbourhood, θ wrapping from 359° to 0°) of cells with
//!   **more than** k votes.
//! - Its middle is the vote-weighted mean of its cells within ±2 columns and ±2 bins of its
//!   highest cell: the mean over the whole zone would be pulled along the long butterfly-shaped
//!   tails of a Hough peak. When two walls' peaks have merged into one zone (a low k), each
//!   local maximum of the zone gets its own centre ([`Zone::peaks`]).

use super::hough::Accumulator;

/// A local maximum of a zone and the (r, θ) of its centre.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Peak {
    /// θ column of the maximum.
    pub t: usize,
    /// r bin of the maximum.
    pub ri: usize,
    /// Votes in the maximum cell.
    pub votes: u32,
    /// Centre r, mm.
    pub r_mm: f64,
    /// Centre θ, degrees `[0, 360)`.
    pub theta_deg: f64,
}

/// A zone: a connected group of Hough cells with more than k votes.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Zone {
    /// The zone's cells as (θ column, r bin).
    pub cells: Vec<(usize, usize)>,
    /// Its local maxima, strongest first; `peaks[0]` is the zone's middle.
    pub peaks: Vec<Peak>,
}

/// The zones of `acc` above the critical value `k`, ordered by their strongest peak.
pub fn find_zones(acc: &Accumulator, k: u32) -> Vec<Zone> {
    LABELS.with(|l| find_zones_with(acc, k, &mut l.borrow_mut()))
}

/// Zone labels of the accumulator's cells, kept between calls: a run extracts thousands of
/// times, and a fresh label array each time (over a megabyte) costs more than the search.
/// A cell belongs to zone `id` of this call when its label is `base + id`; labels below
/// `base` are left over from earlier calls and mean "no zone yet".
struct Labels {
    cells: Vec<u32>,
    base: u32,
}

thread_local! {
    static LABELS: std::cell::RefCell<Labels> =
        const { std::cell::RefCell::new(Labels { cells: Vec::new(), base: 1 }) };
}

fn find_zones_with(acc: &Accumulator, k: u32, labels: &mut Labels) -> Vec<Zone> {
    let (nt, nr) = (acc.n_theta(), acc.n_r());
    // Each call may use up to one label per cell above k: start afresh (all zeros, base 1)
    // when the array is too small or the labels could run out.
    if labels.cells.len() < nt * nr || labels.base as usize >= (u32::MAX as usize) - nt * nr {
        labels.cells.clear();
        labels.cells.resize(nt * nr, 0);
        labels.base = 1;
    }
    let base = labels.base;
    let label = &mut labels.cells[..nt * nr];
    let unlabelled = |l: u32| l < base;
    let mut zones = Vec::new();
    let neighbours = |t: usize, ri: usize| {
        let mut out = [(0usize, 0usize); 8];
        let mut n = 0;
        for dt in [nt - 1, 0, 1] {
            for dr in [-1i64, 0, 1] {
                if dt == 0 && dr == 0 {
                    continue;
                }
                let r2 = ri as i64 + dr;
                if r2 < 0 || r2 >= nr as i64 || (nt == 1 && dt != 0) {
                    continue;
                }
                out[n] = ((t + dt) % nt, r2 as usize);
                n += 1;
            }
        }
        (out, n)
    };
    for t0 in 0..nt {
        // Bins outside the voted band hold no votes, so none is above k.
        for r0 in acc.voted_bins(t0) {
            if acc.get(t0, r0) <= k || !unlabelled(label[t0 * nr + r0]) {
                continue;
            }
            let id = base + zones.len() as u32;
            let mut cells = vec![(t0, r0)];
            label[t0 * nr + r0] = id;
            let mut i = 0;
            while i < cells.len() {
                let (t, ri) = cells[i];
                let (nb, n) = neighbours(t, ri);
                for &(t2, r2) in &nb[..n] {
                    if acc.get(t2, r2) > k && unlabelled(label[t2 * nr + r2]) {
                        label[t2 * nr + r2] = id;
                        cells.push((t2, r2));
                    }
                }
                i += 1;
            }
            let mut peaks: Vec<Peak> = cells
                .iter()
                .filter(|&&(t, ri)| {
                    let v = acc.get(t, ri);
                    let (nb, n) = neighbours(t, ri);
                    nb[..n].iter().all(|&(t2, r2)| {
                        let v2 = acc.get(t2, r2);
                        v2 < v || (v2 == v && (t2, r2) > (t, ri))
                    })
                })
                .map(|&(t, ri)| centre(acc, label, id, t, ri))
                .collect();
            peaks.sort_by(|a, b| b.votes.cmp(&a.votes).then((a.t, a.ri).cmp(&(b.t, b.ri))));
            zones.push(Zone { cells, peaks });
        }
    }
    labels.base = base + zones.len() as u32;
    zones.retain(|z| !z.peaks.is_empty());
    zones.sort_by(|a, b| {
        let (pa, pb) = (&a.peaks[0], &b.peaks[0]);
        pb.votes
            .cmp(&pa.votes)
            .then((pa.t, pa.ri).cmp(&(pb.t, pb.ri)))
    });
    zones
}

/// The vote-weighted centre of zone `id`'s cells within ±2 columns and ±2 bins of (t, ri).
fn centre(acc: &Accumulator, label: &[u32], id: u32, t: usize, ri: usize) -> Peak {
    let (nt, nr) = (acc.n_theta() as i64, acc.n_r() as i64);
    let (mut w, mut sum_dt, mut sum_r) = (0.0, 0.0, 0.0);
    for dt in -2i64..=2 {
        for dr in -2i64..=2 {
            let t2 = (t as i64 + dt).rem_euclid(nt) as usize;
            let r2 = ri as i64 + dr;
            if r2 < 0 || r2 >= nr || label[t2 * nr as usize + r2 as usize] != id {
                continue;
            }
            let v = acc.get(t2, r2 as usize) as f64;
            w += v;
            sum_dt += v * dt as f64;
            sum_r += v * acc.r_mm(r2 as usize);
        }
    }
    let step = acc.theta_step_deg() as f64;
    let theta = acc.theta_deg(t) + step * sum_dt / w.max(1.0);
    Peak {
        t,
        ri,
        votes: acc.get(t, ri),
        r_mm: if w > 0.0 { sum_r / w } else { acc.r_mm(ri) },
        theta_deg: theta.rem_euclid(360.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zones_wrap_around_theta_zero() {
        // A vertical line x = 1500: its peak sits at θ = 0 and spreads to 359° and 1°.
        let pts: Vec<(f64, f64)> = (-20..=20).map(|i| (1500.0, i as f64 * 50.0)).collect();
        let acc = Accumulator::vote(&pts, 1, 50.0);
        let zones = find_zones(&acc, 10);
        let z = zones
            .iter()
            .find(|z| z.peaks[0].r_mm > 1000.0)
            .expect("zone at r = 1500");
        assert!(z.cells.iter().any(|c| c.0 == 359) && z.cells.iter().any(|c| c.0 == 1));
        let p = &z.peaks[0];
        assert!(
            p.theta_deg < 0.5 || p.theta_deg > 359.5,
            "θ {}",
            p.theta_deg
        );
        assert!((p.r_mm - 1500.0).abs() <= 25.0, "r {}", p.r_mm);
    }

    #[test]
    fn two_lines_two_zones_and_k_threshold() {
        let mut pts: Vec<(f64, f64)> = (-20..=20).map(|i| (i as f64 * 50.0, 2000.0)).collect();
        pts.extend((-10..=10).map(|i| (-1500.0, i as f64 * 50.0)));
        let acc = Accumulator::vote(&pts, 1, 50.0);
        let zones = find_zones(&acc, 15);
        assert_eq!(
            zones.len(),
            2,
            "{:?}",
            zones.iter().map(|z| &z.peaks[0]).collect::<Vec<_>>()
        );
        assert_eq!(zones[0].peaks[0].votes, 41, "strongest zone first");
        assert!((zones[0].peaks[0].theta_deg - 90.0).abs() < 0.5);
        assert!((zones[1].peaks[0].theta_deg - 180.0).abs() < 0.5);
        assert!((zones[1].peaks[0].r_mm - 1500.0).abs() <= 25.0);
        // Every cell of a zone has more than k votes; with k = 21 the short line is gone.
        assert!(zones
            .iter()
            .all(|z| z.cells.iter().all(|&(t, r)| acc.get(t, r) > 15)));
        assert_eq!(find_zones(&acc, 21).len(), 1);
        assert!(find_zones(&acc, 41).is_empty());
    }
}
