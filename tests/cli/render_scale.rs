//! Issue 56: `render --scale N` writes a PNG a person can look at (each pixel an N×N block);
//! without it the PNG stays the framebuffer itself, which `diff` and golden images read.

use halfcast::Framebuffer;

use crate::common::{halfcast, halfcast_ok};

#[test]
fn scale_enlarges_every_pixel_into_a_block() {
    let plain = halfcast_ok(&["render", "--size", "37x11", "--angle", "20"]).stdout;
    let plain = Framebuffer::from_image_bytes(&plain).unwrap();
    for n in [2usize, 3, 4, 16] {
        let scale = n.to_string();
        let out = halfcast_ok(&[
            "render", "--size", "37x11", "--angle", "20", "--scale", &scale,
        ]);
        let big = Framebuffer::from_image_bytes(&out.stdout).unwrap();
        assert_eq!((big.width(), big.height()), (37 * n, 22 * n));
        for y in 0..big.height() {
            for x in 0..big.width() {
                assert_eq!(
                    big.get(x, y),
                    plain.get(x / n, y / n),
                    "--scale {n} at {x},{y}"
                );
            }
        }
    }
}

#[test]
fn scale_is_refused_out_of_range_and_for_formats_without_pixels() {
    for bad in ["0", "17", "-1", "two"] {
        let out = halfcast(&["render", "--scale", bad]);
        assert_eq!(out.status.code(), Some(2), "--scale {bad}");
        assert_eq!(
            String::from_utf8_lossy(&out.stderr).lines().count(),
            1,
            "--scale {bad}"
        );
    }
    let out = halfcast(&["render", "--scale", "4", "--format", "ansi"]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "error: --scale enlarges a PNG; --format ansi has no pixels to enlarge\n"
    );
    let out = halfcast(&["render", "--size", "4000x2000", "--scale", "5"]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "error: --scale 5 would make a 20000x20000-pixel PNG; at most 16384 pixels a side\n"
    );
}
