//! Shared fixtures: a small synthetic run, SVG counting, a hash, a JSON checker, temp dirs.

use flock_viz::snapshot::DEPTH_FADE;
use flock_viz::style::{self, AGENT, BACKGROUND};
use flock_viz::{Drawable, Frame, Metrics, Scene};
use glam::{DVec2, DVec3};

/// Agents of the synthetic lattice: 4 columns × 3 rows, spacing 7 (= d), r = 8.4 = 1.2 d.
pub const AGENTS: usize = 12;
/// Frames of the synthetic run.
pub const FRAMES: usize = 5;
/// Edges of the lattice: 3 per row × 3 rows + 4 per column pair × 2 (diagonals are 9.9 > r).
pub const EDGES: usize = 17;

/// 12 agents on a 4 × 3 lattice moving right at 2 m/s, a disc obstacle ahead, a γ-agent at the
/// lattice's centre, 5 frames one second apart.
pub fn lattice_scene() -> Scene {
    let mut scene = Scene::new(2, 8.4).with_title("synthetic lattice");
    for k in 0..FRAMES {
        let t = k as f64;
        let q: Vec<DVec2> = (0..AGENTS)
            .map(|i| DVec2::new((i % 4) as f64 * 7.0 + 2.0 * t, (i / 4) as f64 * 7.0))
            .collect();
        let p = vec![DVec2::new(2.0, 0.0); AGENTS];
        scene = scene.with_frame(Frame::from_vectors(t, &q, &p));
    }
    scene
        .with_obstacle(Drawable::ball(DVec2::new(36.0, 7.0), 4.0))
        .with_gamma(|t| DVec3::new(10.5 + 2.0 * t, 7.0, 0.0))
}

/// 27 agents on a 3 × 3 × 3 lattice moving along (1, 0.3, 0.2), a ball and a box, 3 frames.
pub fn cube_scene() -> Scene {
    let mut scene = Scene::new(3, 8.4).with_title("synthetic cube");
    for k in 0..3 {
        let t = k as f64;
        let q: Vec<DVec3> = (0..27)
            .map(|i| {
                DVec3::new(
                    (i % 3) as f64 * 7.0 + t,
                    ((i / 3) % 3) as f64 * 7.0,
                    (i / 9) as f64 * 7.0,
                )
            })
            .collect();
        scene = scene.with_frame(Frame::new(t, q, vec![DVec3::new(1.0, 0.3, 0.2); 27]));
    }
    scene
        .with_obstacle(Drawable::ball(DVec3::new(25.0, 7.0, 7.0), 3.0))
        .with_obstacle(Drawable::cuboid(
            DVec3::new(-8.0, 7.0, 7.0),
            DVec3::new(2.0, 4.0, 6.0),
        ))
}

/// Metrics of a run that flocks: every column flocking writes, and obstacle clearance.
pub fn flocking_metrics(with_clearance: bool) -> Metrics {
    let t: Vec<f64> = (0..50).map(|k| k as f64 * 0.5).collect();
    let map = |f: fn(f64) -> f64| t.iter().map(|&t| f(t)).collect::<Vec<f64>>();
    let mut columns = vec![
        ("t".to_owned(), t.clone()),
        ("connectivity".to_owned(), map(|t| (t / 10.0).min(1.0))),
        (
            "giant_component".to_owned(),
            map(|t| (0.3 + t / 10.0).min(1.0)),
        ),
        (
            "cohesion_radius".to_owned(),
            map(|t| 40.0 + 60.0 * (-t / 5.0).exp()),
        ),
        ("deviation_energy".to_owned(), map(|t| 1e-4 + (-t).exp())),
        (
            "velocity_mismatch".to_owned(),
            map(|t| if t == 0.0 { 0.0 } else { (-t).exp() }),
        ),
        ("min_distance".to_owned(), map(|t| 6.5 - 2.0 * (-t).exp())),
        ("collisions".to_owned(), map(|_| 0.0)),
        ("energy".to_owned(), map(|t| 100.0 * (-t).exp() - 50.0)),
    ];
    if with_clearance {
        columns.push(("obstacle_clearance".to_owned(), map(|t| 10.0 - 0.1 * t)));
        columns.push(("inside_obstacles".to_owned(), map(|_| 0.0)));
    }
    Metrics::from_columns(columns).unwrap()
}

/// How many `<tag` elements of `svg` have `attribute="#RRGGBB"` of `colour`.
pub fn count_marks(svg: &str, tag: &str, attribute: &str, colour: [u8; 3]) -> usize {
    let needle = format!("{attribute}=\"{}\"", style::hex(colour));
    svg.split('<')
        .filter(|element| element.starts_with(&format!("{tag} ")))
        .filter(|element| element.split('>').next().unwrap_or("").contains(&needle))
        .count()
}

/// The agent markers of an SVG: triangles and (for agents at rest) dots, in the agents' colour or
/// (3D panels, depth-cued) a shade of it.
pub fn agent_markers(svg: &str) -> usize {
    agent_fades(svg).len()
}

/// How far each agent marker of an SVG is faded towards the background, in drawing order: 0 for
/// [`AGENT`] itself, [`DEPTH_FADE`] for the farthest agent of a depth-cued 3D panel.
pub fn agent_fades(svg: &str) -> Vec<f64> {
    svg.split('<')
        .filter(|element| element.starts_with("polygon ") || element.starts_with("circle "))
        .filter_map(|element| {
            let fill = element.split("fill=\"#").nth(1)?.get(..6)?;
            let channel = |k: usize| u8::from_str_radix(&fill[2 * k..2 * k + 2], 16).ok();
            let colour = [channel(0)?, channel(1)?, channel(2)?];
            // the fades that give each channel its value: an interval per channel, to intersect
            let (lo, hi) = (0..3).fold((0.0_f64, DEPTH_FADE), |(lo, hi), k| {
                let (a, b, v) = (
                    f64::from(AGENT[k]),
                    f64::from(BACKGROUND[k]),
                    f64::from(colour[k]),
                );
                (
                    lo.max((v - 0.5 - a) / (b - a)),
                    hi.min((v + 0.5 - a) / (b - a)),
                )
            });
            (lo <= hi).then_some(lo.max(0.0))
        })
        .collect()
}

/// FNV-1a, 64 bits: a hash that is the same on every run and machine.
pub fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// A fresh empty directory for a test, of a name no other holds, created and removed (when
/// dropped) by tempfile alone: a test removes nothing by path.
pub fn temp_dir(name: &str) -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix(&format!("flock-viz-{name}-"))
        .tempdir()
        .unwrap()
}

/// A JSON value, as the player's data is checked.
#[derive(Clone, Debug, PartialEq)]
pub enum Json {
    Null,
    Bool(bool),
    Number(f64),
    String(String),
    Array(Vec<Json>),
    Object(Vec<(String, Json)>),
}

impl Json {
    /// Parses a complete JSON text (RFC 8259), or says where it is malformed.
    pub fn parse(text: &str) -> Result<Json, String> {
        let mut p = JsonParser {
            s: text.as_bytes(),
            i: 0,
        };
        let v = p.value()?;
        p.ws();
        if p.i != p.s.len() {
            return Err(format!("trailing characters at byte {}", p.i));
        }
        Ok(v)
    }

    /// The member `key` of an object.
    pub fn get(&self, key: &str) -> Option<&Json> {
        match self {
            Json::Object(members) => members.iter().find(|(k, _)| k == key).map(|(_, v)| v),
            _ => None,
        }
    }

    /// The elements of an array.
    pub fn array(&self) -> &[Json] {
        match self {
            Json::Array(a) => a,
            _ => panic!("not an array: {self:?}"),
        }
    }
}

struct JsonParser<'a> {
    s: &'a [u8],
    i: usize,
}

impl JsonParser<'_> {
    fn ws(&mut self) {
        while self.i < self.s.len() && b" \t\r\n".contains(&self.s[self.i]) {
            self.i += 1;
        }
    }

    fn eat(&mut self, c: u8) -> Result<(), String> {
        self.ws();
        if self.s.get(self.i) == Some(&c) {
            self.i += 1;
            Ok(())
        } else {
            Err(format!("expected {:?} at byte {}", c as char, self.i))
        }
    }

    fn value(&mut self) -> Result<Json, String> {
        self.ws();
        match self.s.get(self.i) {
            Some(b'{') => {
                self.i += 1;
                let mut members = Vec::new();
                self.ws();
                if self.s.get(self.i) == Some(&b'}') {
                    self.i += 1;
                    return Ok(Json::Object(members));
                }
                loop {
                    self.ws();
                    let Json::String(key) = self.value()? else {
                        return Err(format!("object key is not a string at byte {}", self.i));
                    };
                    self.eat(b':')?;
                    members.push((key, self.value()?));
                    self.ws();
                    match self.s.get(self.i) {
                        Some(b',') => self.i += 1,
                        Some(b'}') => {
                            self.i += 1;
                            return Ok(Json::Object(members));
                        }
                        _ => return Err(format!("expected , or }} at byte {}", self.i)),
                    }
                }
            }
            Some(b'[') => {
                self.i += 1;
                let mut items = Vec::new();
                self.ws();
                if self.s.get(self.i) == Some(&b']') {
                    self.i += 1;
                    return Ok(Json::Array(items));
                }
                loop {
                    items.push(self.value()?);
                    self.ws();
                    match self.s.get(self.i) {
                        Some(b',') => self.i += 1,
                        Some(b']') => {
                            self.i += 1;
                            return Ok(Json::Array(items));
                        }
                        _ => return Err(format!("expected , or ] at byte {}", self.i)),
                    }
                }
            }
            Some(b'"') => {
                self.i += 1;
                let mut out = String::new();
                loop {
                    match self.s.get(self.i) {
                        None => return Err("unterminated string".into()),
                        Some(b'"') => {
                            self.i += 1;
                            return Ok(Json::String(out));
                        }
                        Some(b'\\') => {
                            let e = *self.s.get(self.i + 1).ok_or("bad escape")?;
                            self.i += 2;
                            match e {
                                b'"' => out.push('"'),
                                b'\\' => out.push('\\'),
                                b'/' => out.push('/'),
                                b'n' => out.push('\n'),
                                b't' => out.push('\t'),
                                b'r' => out.push('\r'),
                                b'b' => out.push('\u{8}'),
                                b'f' => out.push('\u{c}'),
                                b'u' => {
                                    let hex = std::str::from_utf8(&self.s[self.i..self.i + 4])
                                        .map_err(|e| e.to_string())?;
                                    let code =
                                        u32::from_str_radix(hex, 16).map_err(|e| e.to_string())?;
                                    out.push(char::from_u32(code).ok_or("bad \\u escape")?);
                                    self.i += 4;
                                }
                                _ => return Err(format!("bad escape at byte {}", self.i)),
                            }
                        }
                        Some(&c) if c < 0x20 => {
                            return Err(format!("control character in string at {}", self.i));
                        }
                        Some(_) => {
                            let rest = std::str::from_utf8(&self.s[self.i..])
                                .map_err(|e| e.to_string())?;
                            let c = rest.chars().next().unwrap();
                            out.push(c);
                            self.i += c.len_utf8();
                        }
                    }
                }
            }
            Some(b't') if self.s[self.i..].starts_with(b"true") => {
                self.i += 4;
                Ok(Json::Bool(true))
            }
            Some(b'f') if self.s[self.i..].starts_with(b"false") => {
                self.i += 5;
                Ok(Json::Bool(false))
            }
            Some(b'n') if self.s[self.i..].starts_with(b"null") => {
                self.i += 4;
                Ok(Json::Null)
            }
            Some(c) if *c == b'-' || c.is_ascii_digit() => {
                let start = self.i;
                self.i += 1;
                while self.i < self.s.len() && b"0123456789.eE+-".contains(&self.s[self.i]) {
                    self.i += 1;
                }
                let text = std::str::from_utf8(&self.s[start..self.i]).unwrap();
                let digits = text.strip_prefix('-').unwrap_or(text);
                let leading_zero =
                    digits.len() > 1 && digits.starts_with('0') && !digits.starts_with("0.");
                let valid = !leading_zero && !text.ends_with('.');
                match text.parse::<f64>() {
                    Ok(v) if valid => Ok(Json::Number(v)),
                    _ => Err(format!("bad number {text:?} at byte {start}")),
                }
            }
            _ => Err(format!("unexpected character at byte {}", self.i)),
        }
    }
}

#[test]
fn the_json_checker_accepts_json_and_refuses_the_rest() {
    let v = Json::parse(r#"{"a":[1,-2.5,1e-3,null,true],"b":"x\u003cy"}"#).unwrap();
    assert_eq!(v.get("a").unwrap().array().len(), 5);
    assert_eq!(v.get("b"), Some(&Json::String("x<y".into())));
    for bad in ["{", "[1,]", "01", "1.", "{\"a\" 1}", "nan", "[1] x"] {
        assert!(Json::parse(bad).is_err(), "{bad}");
    }
}

/// A decoded RGB PNG: its size and its pixels, row by row.
pub struct Decoded {
    /// Width and height in pixels.
    pub size: (u32, u32),
    /// The pixels.
    pub pixels: Vec<[u8; 3]>,
}

/// Decodes an 8-bit RGB PNG.
pub fn decode_png(bytes: &[u8]) -> Decoded {
    let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .expect("a PNG header");
    let mut buffer = vec![0; reader.output_buffer_size().expect("a bounded image")];
    let info = reader.next_frame(&mut buffer).expect("PNG data");
    assert_eq!(info.color_type, png::ColorType::Rgb, "an RGB image");
    let pixels = buffer[..info.buffer_size()]
        .chunks_exact(3)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    Decoded {
        size: (info.width, info.height),
        pixels,
    }
}

/// The default snapshot options with their panel style changed by `edit`.
pub fn styled(edit: impl FnOnce(&mut flock_viz::PanelStyle)) -> flock_viz::SnapshotOptions {
    let mut options = flock_viz::SnapshotOptions::default();
    edit(&mut options.style);
    options
}
