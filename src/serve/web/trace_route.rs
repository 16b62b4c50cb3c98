//! The ray debugger's data and its export: `/trace.json`, `/trace.svg` and `/trace.png` take a
//! ray's address (`pos=X,Y&angle=A&column=C&size=COLSxROWS[&fov=F][&map=NAME]`, the values
//! `halfcast trace` takes) and answer from [`crate::trace_query`], the library `trace` itself
//! runs, so the figure a page exports is byte for byte the one `trace` writes. A bad address
//! gets 400 and `trace`'s message.

use std::sync::Arc;

use super::edge::WebEdge;
use crate::trace_query::address::{address_of, TraceAddress};
use crate::world::World;

/// What a trace route answers: a status, a content type and a body.
#[derive(Debug)]
pub struct Answer {
    /// 200, or 400 for a bad address.
    pub status: u16,
    /// The body's content type.
    pub kind: &'static str,
    /// The JSON, SVG, PNG or message.
    pub body: Vec<u8>,
}

/// The trace routes' forms, by path.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Form {
    /// `/trace.json`: the figure's data.
    Json,
    /// `/trace.svg`: the figure.
    Svg,
    /// `/trace.png`: the figure painted.
    Png,
}

impl Form {
    /// The form a path asks for, if it is a trace route.
    #[must_use]
    pub fn of(path: &str) -> Option<Self> {
        match path {
            "/trace.json" => Some(Self::Json),
            "/trace.svg" => Some(Self::Svg),
            "/trace.png" => Some(Self::Png),
            _ => None,
        }
    }
}

/// Answers the trace route at `path` for the address `query` on the edge's served maps.
pub async fn answer(path: &str, query: &str, edge: &WebEdge) -> Answer {
    let Some(form) = Form::of(path) else {
        return Answer {
            status: 404,
            kind: "text/plain",
            body: b"not found\n".to_vec(),
        };
    };
    let maps = edge.shared.maps.clone();
    let query = query.to_owned();
    // One column's cast is quick, but painting a PNG is not free: off the network threads.
    tokio::task::spawn_blocking(move || traced(form, &query, &maps))
        .await
        .unwrap_or_else(|e| bad(format!("the trace failed: {e}")))
}

/// The answer, worked out.
fn traced(form: Form, query: &str, maps: &[Arc<World>]) -> Answer {
    let address = match TraceAddress::read(query) {
        Ok(a) => a,
        Err(e) => return bad(e),
    };
    let world = match &address.map {
        None => maps.first(),
        Some(name) => maps.iter().find(|w| &w.map.name == name),
    };
    let Some(world) = world else {
        let names: Vec<&str> = maps.iter().map(|w| w.map.name.as_str()).collect();
        return bad(format!(
            "no served map is named '{}' (served: {})",
            address.map.unwrap_or_default(),
            names.join(", ")
        ));
    };
    let ray = match address.query.trace(world) {
        Ok(r) => r,
        Err(e) => return bad(e),
    };
    match form {
        Form::Json => {
            // The map is named in the link only when there is a choice of maps.
            let map = (maps.len() > 1).then_some(world.map.name.as_str());
            // The values as asked (the camera's own would print 3.7 as 3.7000000000000006);
            // the map's start where the address left them out.
            let q = &address.query;
            let pos = q.pos.unwrap_or(ray.camera.pos);
            let angle = q.angle.unwrap_or_else(|| ray.camera.heading_deg());
            let link = address_of(q, pos, angle, map);
            ok(
                "application/json",
                ray.data(world, link).to_json().into_bytes(),
            )
        }
        Form::Svg => ok("image/svg+xml", ray.svg(&world.map).into_bytes()),
        Form::Png => match ray.png(&world.map) {
            Ok(png) => ok("image/png", png),
            Err(e) => bad(e),
        },
    }
}

fn ok(kind: &'static str, body: Vec<u8>) -> Answer {
    Answer {
        status: 200,
        kind,
        body,
    }
}

fn bad(message: String) -> Answer {
    Answer {
        status: 400,
        kind: "text/plain; charset=utf-8",
        body: format!("{message}\n").into_bytes(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn maps() -> Vec<Arc<World>> {
        vec![Arc::new(World::default_world())]
    }

    #[test]
    fn a_good_address_answers_each_form_and_a_bad_one_says_why() {
        let q = "pos=15.5,5.5&angle=90&column=20&size=40x12";
        let json = traced(Form::Json, q, &maps());
        assert_eq!((json.status, json.kind), (200, "application/json"));
        let text = String::from_utf8(json.body).unwrap();
        assert!(text.contains("\"address\":\"pos=15.5,5.5&angle=90&column=20&size=40x12\""));
        let odd = traced(
            Form::Json,
            "pos=15.5,5.5&angle=3.7&column=1&size=40x12",
            &maps(),
        );
        let odd = String::from_utf8(odd.body).unwrap();
        assert!(odd.contains("&angle=3.7&"), "{odd}");
        let svg = traced(Form::Svg, q, &maps());
        assert!(svg.body.starts_with(b"<svg") || svg.body.starts_with(b"<?xml"));
        assert!(traced(Form::Png, q, &maps()).body.starts_with(b"\x89PNG"));
        let wall = traced(Form::Svg, "pos=0.5,0.5&column=1", &maps());
        assert_eq!(wall.status, 400);
        assert!(String::from_utf8(wall.body)
            .unwrap()
            .contains("is inside a wall"));
        let unknown = traced(Form::Json, "column=1&map=nowhere.cub", &maps());
        assert_eq!(unknown.status, 400);
    }
}
