//! Which rule made a `setOdometry`, and on what evidence: the walls it paired, the sonar and
//! the angle at which that sonar meets the wall. Read from working memory right after the
//! decision that selected the correcting operator, before the operator applies (the walls
//! still carry their times then).
//!
//! - Hypothesis 2 (`ChangeRobotPosition` in the CheckWallRelation substate) pairs two walls:
//!   the top state's CheckWallRelation operator names them (`^Wall1 ^Wall2`); the one with the
//!   earlier `^Time` is the map wall, trusted, and the later one the new sighting.
//! - ChangeRobotPosition2 pairs one map wall with one sonar reading: its `^difference` names
//!   the wall, the sonar `^index` and `^diff` (virtual minus sonar range); the wall's
//!   `^distance` for that sonar is the virtual range. The incidence is the angle between the
//!   sonar's axis (believed heading plus the sonar's angle) and the wall's normal, in
//!   [0°, 90°]. `nearest` says whether no other map wall gives that sonar a shorter positive
//!   virtual range (when it does, the paired wall is hidden behind another).

use std::fmt::Write as _;

use rusoar::{Agent, Symbol as Sym};

/// The rule that issued a correction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum Rule {
    /// Hypothesis 2: `slam*CheckWallRelation*Condition2*Apply*change*robot*position`.
    Hypothesis2,
    /// `slam*apply*change*robot*position2`.
    ChangeRobotPosition2,
    /// Rules v2, `v2*apply*correct`: heading and offset along one map wall's normal.
    V2Wall,
    /// Rules v2, `v2*apply*heading`: heading only, from a wall matched to no map wall.
    V2Heading,
    /// No correcting operator was found for it.
    #[default]
    Unknown,
}

impl Rule {
    /// The name in the log.
    pub fn name(self) -> &'static str {
        match self {
            Rule::Hypothesis2 => "hypothesis2",
            Rule::ChangeRobotPosition2 => "crp2",
            Rule::V2Wall => "v2-correct",
            Rule::V2Heading => "v2-heading",
            Rule::Unknown => "unknown",
        }
    }
}

/// A wall the correction used: its identifier and `^Time` (the step of the extraction that
/// produced it, or of the earlier wall it was moved onto).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct WallRef {
    pub id: String,
    pub time: f64,
}

/// What a correction was based on. Fields that do not apply to its rule are `None`.
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Attribution {
    pub rule: Rule,
    /// The remembered wall trusted by the correction.
    pub map_wall: Option<WallRef>,
    /// Hypothesis 2: the later sighting moved onto the map wall.
    pub new_wall: Option<WallRef>,
    /// ChangeRobotPosition2: the sonar compared with the map wall.
    pub sonar: Option<u8>,
    /// Its reading, mm.
    pub sonar_mm: Option<f64>,
    /// The range `getwalldistance` gave for the map wall, mm.
    pub virtual_mm: Option<f64>,
    /// Angle between the sonar's axis and the wall's normal, degrees in [0, 90].
    pub incidence_deg: Option<f64>,
    /// Whether the map wall is the nearest one that sonar's ray meets.
    pub nearest: Option<bool>,
    /// Hypothesis 2: `^r-diff` (mm) and `^th-diff` (degrees) of the operator.
    pub r_diff: Option<f64>,
    pub th_diff: Option<f64>,
}

/// The CSV columns matching [`Attribution::csv_fields`].
pub const HEADER: &str = "rule,map_wall,map_wall_time,new_wall,new_wall_time,sonar,sonar_mm,\
virtual_mm,incidence_deg,nearest,r_diff_mm,th_diff_deg";

impl Attribution {
    /// The fields of [`HEADER`], comma-separated; empty where they do not apply.
    pub fn csv_fields(&self) -> String {
        let mut s = String::from(self.rule.name());
        let opt = |s: &mut String, v: Option<f64>, decimals: usize| {
            s.push(',');
            if let Some(v) = v {
                let _ = write!(s, "{v:.decimals$}");
            }
        };
        for w in [&self.map_wall, &self.new_wall] {
            s.push(',');
            if let Some(w) = w {
                s.push_str(&w.id);
            }
            opt(&mut s, w.as_ref().map(|w| w.time), 0);
        }
        opt(&mut s, self.sonar.map(f64::from), 0);
        opt(&mut s, self.sonar_mm, 0);
        opt(&mut s, self.virtual_mm, 0);
        opt(&mut s, self.incidence_deg, 1);
        s.push(',');
        if let Some(n) = self.nearest {
            s.push_str(if n { "true" } else { "false" });
        }
        opt(&mut s, self.r_diff, 1);
        opt(&mut s, self.th_diff, 1);
        s
    }
}

/// Reads working memory by attribute name.
struct Reader<'a> {
    a: &'a Agent,
}

impl Reader<'_> {
    fn get(&self, id: Sym, attr: &str) -> Option<Sym> {
        let attr = self.a.find_string(attr)?;
        self.a
            .children(id)
            .iter()
            .find(|w| w.attr == attr && !w.acceptable)
            .map(|w| w.value)
    }

    fn all(&self, id: Sym, attr: &str) -> Vec<Sym> {
        let Some(attr) = self.a.find_string(attr) else {
            return Vec::new();
        };
        self.a
            .children(id)
            .iter()
            .filter(|w| w.attr == attr && !w.acceptable)
            .map(|w| w.value)
            .collect()
    }

    fn num(&self, id: Sym, attr: &str) -> Option<f64> {
        self.get(id, attr)
            .and_then(|v| self.a.value_of(v).as_number())
    }

    fn is(&self, id: Sym, attr: &str, text: &str) -> bool {
        self.get(id, attr).is_some_and(|v| self.a.text(v) == text)
    }

    fn wall(&self, w: Sym) -> WallRef {
        WallRef {
            id: self.a.text(w),
            time: self.num(w, "Time").unwrap_or(f64::NAN),
        }
    }

    /// The virtual range of wall `w` for sonar `i`.
    fn virtual_range(&self, w: Sym, i: f64) -> Option<f64> {
        self.all(w, "distance")
            .into_iter()
            .find(|d| self.num(*d, "index") == Some(i))
            .and_then(|d| self.num(d, "range"))
    }
}

/// The attribution of the correcting operator the last decision selected, if it selected one
/// (`operators`: the names the decision's trace shows).
pub fn read(agent: &Agent, operators: &[String]) -> Option<Attribution> {
    let r = Reader { a: agent };
    let top = agent.top_state();
    let op = r.get(top, "operator")?;
    if operators.iter().any(|o| o == "ChangeRobotPosition2")
        && r.is(op, "name", "ChangeRobotPosition2")
    {
        return Some(crp2(&r, top, op));
    }
    for (name, rule) in [
        ("v2-correct", Rule::V2Wall),
        ("v2-heading", Rule::V2Heading),
    ] {
        if operators.iter().any(|o| o == name) && r.is(op, "name", name) {
            return Some(v2(&r, op, rule));
        }
    }
    if operators.iter().any(|o| o == "ChangeRobotPosition") && r.is(op, "name", "CheckWallRelation")
    {
        let (w1, w2) = (r.get(op, "Wall1")?, r.get(op, "Wall2")?);
        let (a, b) = (r.wall(w1), r.wall(w2));
        let (map, new, dr, dth) = if b.time < a.time {
            (b, a, w2, w1)
        } else {
            (a, b, w1, w2)
        };
        let th_diff = match (r.num(dr, "Th"), r.num(dth, "Th")) {
            (Some(t1), Some(t2)) => Some(t1 - t2),
            _ => None,
        };
        let r_diff = match (r.num(dr, "R"), r.num(dth, "R")) {
            (Some(r1), Some(r2)) => Some(r1 - r2),
            _ => None,
        };
        return Some(Attribution {
            rule: Rule::Hypothesis2,
            map_wall: Some(map),
            new_wall: Some(new),
            r_diff,
            th_diff,
            ..Attribution::default()
        });
    }
    None
}

/// A rules-v2 correction's evidence: the observation's wall (`new_wall`), the map wall it
/// matched (`map_wall`), the offset along the normal (`r_diff`) and the heading error
/// (`th_diff`).
fn v2(r: &Reader, op: Sym, rule: Rule) -> Attribution {
    let obs = r.get(op, "obs");
    let pair = r.get(op, "pair");
    Attribution {
        rule,
        new_wall: obs.and_then(|o| r.get(o, "wall")).map(|w| r.wall(w)),
        map_wall: pair.and_then(|p| r.get(p, "map")).map(|w| r.wall(w)),
        r_diff: pair.and_then(|p| r.num(p, "d")),
        th_diff: obs.and_then(|o| r.num(o, "e")),
        ..Attribution::default()
    }
}

/// ChangeRobotPosition2's evidence.
fn crp2(r: &Reader, top: Sym, op: Sym) -> Attribution {
    let mut at = Attribution {
        rule: Rule::ChangeRobotPosition2,
        ..Attribution::default()
    };
    let Some(pd) = r.get(op, "difference") else {
        return at;
    };
    let (Some(w), Some(i)) = (r.get(pd, "Wall"), r.num(pd, "index")) else {
        return at;
    };
    at.map_wall = Some(r.wall(w));
    at.sonar = (0.0..=255.0).contains(&i).then_some(i as u8);
    let dist1 = r.virtual_range(w, i);
    at.virtual_mm = dist1;
    at.sonar_mm = match (dist1, r.num(pd, "diff")) {
        (Some(v), Some(d)) => Some(v - d),
        _ => None,
    };
    let heading = r
        .get(top, "io")
        .and_then(|io| r.get(io, "input-link"))
        .and_then(|il| r.get(il, "currentrobotdata"))
        .and_then(|c| r.num(c, "Th"));
    if let (Some(th), Some(a), Some(normal)) = (heading, r.num(pd, "angle"), r.num(w, "Th")) {
        at.incidence_deg = Some(incidence(th + a, normal));
    }
    if let (Some(d1), Some(wd)) = (dist1, r.get(top, "wallData")) {
        let hidden = r
            .all(wd, "Wall")
            .into_iter()
            .filter(|o| *o != w)
            .filter_map(|o| r.virtual_range(o, i))
            .any(|d| d > 0.0 && d < d1);
        at.nearest = Some(!hidden);
    }
    at
}

/// The angle between a ray heading `ray_deg` and a line whose normal points at `normal_deg`,
/// folded into [0°, 90°] (0: the ray meets the wall head-on).
pub fn incidence(ray_deg: f64, normal_deg: f64) -> f64 {
    let d = (ray_deg - normal_deg).rem_euclid(180.0);
    d.min(180.0 - d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn incidence_folds_into_a_quarter_turn() {
        assert_eq!(incidence(0.0, 0.0), 0.0);
        assert_eq!(incidence(180.0, 0.0), 0.0);
        assert_eq!(incidence(30.0, 0.0), 30.0);
        assert_eq!(incidence(-30.0, 0.0), 30.0);
        assert_eq!(incidence(350.0, 20.0), 30.0);
        assert_eq!(incidence(90.0, 0.0), 90.0);
    }

    #[test]
    fn csv_fields_leave_what_does_not_apply_empty() {
        let a = Attribution {
            rule: Rule::ChangeRobotPosition2,
            map_wall: Some(WallRef {
                id: "W12".into(),
                time: 75.0,
            }),
            sonar: Some(3),
            sonar_mm: Some(1234.0),
            virtual_mm: Some(1400.0),
            incidence_deg: Some(12.25),
            nearest: Some(false),
            ..Attribution::default()
        };
        assert_eq!(a.csv_fields(), "crp2,W12,75,,,3,1234,1400,12.2,false,,");
        assert_eq!(HEADER.split(',').count(), a.csv_fields().split(',').count());
        assert_eq!(Attribution::default().csv_fields(), "unknown,,,,,,,,,,,");
    }
}
