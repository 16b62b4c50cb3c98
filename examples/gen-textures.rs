//! Writes the project's procedural textures into `textures/` (deterministic).

use halfcast::texture::{generate, sprite_art};

fn main() -> anyhow::Result<()> {
    let dir = std::env::args()
        .nth(1)
        .unwrap_or_else(|| concat!(env!("CARGO_MANIFEST_DIR"), "/textures").to_owned());
    std::fs::create_dir_all(&dir)?;
    for (name, make) in generate::ALL {
        let path = format!("{dir}/{name}.png");
        std::fs::write(&path, make().to_png().map_err(anyhow::Error::msg)?)?;
        println!("wrote {path}");
    }
    std::fs::create_dir_all(format!("{dir}/sprites"))?;
    for (name, make) in sprite_art::ALL {
        let path = format!("{dir}/sprites/{name}.png");
        std::fs::write(&path, make().to_png().map_err(anyhow::Error::msg)?)?;
        println!("wrote {path}");
    }
    Ok(())
}
