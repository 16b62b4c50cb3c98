//! A bordered box centred over whatever is drawn below it: the help and the results screen.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::{Block, Clear, Widget};

/// Clears a `size` (columns, rows) box in the middle of `area` (shrunk to fit), draws `block`
/// around it and returns the inside; `None` when `area` is too small for a box at all.
pub fn draw(area: Rect, size: (u16, u16), block: Block, buf: &mut Buffer) -> Option<Rect> {
    let (w, h) = (size.0.min(area.width), size.1.min(area.height));
    if w < 4 || h < 3 {
        return None;
    }
    let r = Rect::new(
        area.x + (area.width - w) / 2,
        area.y + (area.height - h) / 2,
        w,
        h,
    );
    Clear.render(r, buf);
    let inner = block.inner(r);
    block.render(r, buf);
    Some(inner)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_box_is_centred_clipped_to_the_area_and_skipped_when_there_is_no_room() {
        let area = Rect::new(0, 0, 20, 10);
        let mut buf = Buffer::empty(area);
        let inner = draw(area, (10, 4), Block::bordered(), &mut buf);
        assert_eq!(inner, Some(Rect::new(6, 4, 8, 2)));
        assert_eq!(buf[(5, 3)].symbol(), "┌");
        let inner = draw(area, (40, 40), Block::bordered(), &mut buf);
        assert_eq!(inner, Some(Rect::new(1, 1, 18, 8)));
        assert_eq!(
            draw(Rect::new(0, 0, 3, 2), (10, 4), Block::bordered(), &mut buf),
            None
        );
    }
}
