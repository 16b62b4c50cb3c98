//! A ray as a page's address carries it: `pos=X,Y&angle=A&column=C&size=COLSxROWS[&fov=F]
//! [&map=NAME]`, the values `halfcast trace` takes as `--pos --angle --column --size --fov`
//! (and the served map's name). A bad value is refused with the message `trace` prints for it.

use super::values::{parse_finite, parse_fov, parse_pos, parse_size};
use super::TraceQuery;
use crate::render::derivation::num_with;

/// A ray's address read: the query, and the map it names (`None`: the server's first).
#[derive(Debug, Clone, PartialEq)]
pub struct TraceAddress {
    /// The pose, view size and column.
    pub query: TraceQuery,
    /// The served map's name (`Map::name`), when the address gives one.
    pub map: Option<String>,
}

/// `invalid value 'V' for '--FLAG <NAME>': why` — clap's words for a bad flag value.
fn invalid(value: &str, flag: &str, why: &str) -> String {
    let name = flag.to_ascii_uppercase();
    format!("invalid value '{value}' for '--{flag} <{name}>': {why}")
}

impl TraceAddress {
    /// Reads an address's query (after `?`, percent-escaped); keys it does not know are left
    /// alone (a page may add its own).
    ///
    /// # Errors
    /// The message `halfcast trace` prints for the first bad value, or for a missing column.
    pub fn read(query: &str) -> Result<Self, String> {
        let mut q = TraceQuery::column(0);
        let mut column = None;
        let mut map = None;
        for pair in query.split('&').filter(|p| !p.is_empty()) {
            let (k, v) = pair.split_once('=').unwrap_or((pair, ""));
            let v = percent_decoded(v);
            let bad = |why: String| invalid(&v, k, &why);
            match k {
                "pos" => q.pos = Some(parse_pos(&v).map_err(bad)?),
                "angle" => q.angle = Some(parse_finite(&v).map_err(bad)?),
                "fov" => q.fov = parse_fov(&v).map_err(bad)?,
                "size" => q.size = parse_size(&v).map_err(bad)?,
                "column" => column = Some(v.parse::<usize>().map_err(|e| bad(e.to_string()))?),
                "map" => map = Some(v),
                _ => {}
            }
        }
        q.column = column.ok_or_else(|| {
            "the following required arguments were not provided: --column <COLUMN>".to_owned()
        })?;
        Ok(Self { query: q, map })
    }
}

/// The address's query for a ray cast from `pos` facing `angle` (what the page links to):
/// `fov` only when it is not the default, the map when one is named.
#[must_use]
pub fn address_of(q: &TraceQuery, pos: crate::vec2::Vec2, angle: f64, map: Option<&str>) -> String {
    let mut out = format!(
        "pos={},{}&angle={}&column={}&size={}x{}",
        short(pos.x),
        short(pos.y),
        short(angle),
        q.column,
        q.size.0,
        q.size.1
    );
    if (q.fov - crate::camera::DEFAULT_FOV_DEG).abs() > 1e-9 {
        out.push_str(&format!("&fov={}", short(q.fov)));
    }
    if let Some(m) = map {
        out.push_str("&map=");
        out.push_str(&percent_encoded(m));
    }
    out
}

/// A number in the shortest form that reads back as itself.
fn short(v: f64) -> String {
    let s = format!("{v}");
    if s.parse::<f64>() == Ok(v) {
        s
    } else {
        num_with(v, 6)
    }
}

/// `%xx` escapes and `+` decoded; malformed escapes kept as they are (any address's query).
#[must_use]
pub fn percent_decoded(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        match b[i] {
            b'%' if i + 2 < b.len() => match (hex(b[i + 1]), hex(b[i + 2])) {
                (Some(h), Some(l)) => {
                    out.push((h * 16 + l) as u8);
                    i += 3;
                    continue;
                }
                _ => out.push(b'%'),
            },
            b'+' => out.push(b' '),
            c => out.push(c),
        }
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Everything but letters, digits and `-._~` escaped as `%xx`.
fn percent_encoded(s: &str) -> String {
    s.bytes()
        .map(|c| {
            if c.is_ascii_alphanumeric() || b"-._~".contains(&c) {
                (c as char).to_string()
            } else {
                format!("%{c:02X}")
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vec2::Vec2;

    #[test]
    fn an_address_reads_as_trace_flags_and_writes_back_the_same() {
        let a = TraceAddress::read("pos=15.3%2C5.6&angle=62&column=39&size=50x23&map=heights.cub")
            .unwrap();
        assert_eq!(a.query.pos, Some(Vec2::new(15.3, 5.6)));
        assert_eq!((a.query.angle, a.query.column), (Some(62.0), 39));
        assert_eq!(a.query.size, (50, 23));
        assert_eq!(a.map.as_deref(), Some("heights.cub"));
        assert_eq!(
            address_of(&a.query, Vec2::new(15.3, 5.6), 62.0, a.map.as_deref()),
            "pos=15.3,5.6&angle=62&column=39&size=50x23&map=heights.cub"
        );
        let mut q = a.query;
        q.fov = 90.0;
        assert!(address_of(&q, Vec2::new(1.0, 2.0), 0.0, None).ends_with("&fov=90"));
    }

    #[test]
    fn bad_values_get_trace_s_messages() {
        assert_eq!(
            TraceAddress::read("pos=abc&column=1").unwrap_err(),
            "invalid value 'abc' for '--pos <POS>': 'abc' is not X,Y"
        );
        assert_eq!(
            TraceAddress::read("column=x").unwrap_err(),
            "invalid value 'x' for '--column <COLUMN>': invalid digit found in string"
        );
        assert!(TraceAddress::read("pos=1,2")
            .unwrap_err()
            .contains("--column <COLUMN>"));
        assert!(TraceAddress::read("size=0x3&column=0")
            .unwrap_err()
            .contains("is out of range"));
        assert_eq!(percent_decoded("a%2"), "a%2");
        assert_eq!(percent_decoded("%41+b%2c"), "A b,");
    }
}
