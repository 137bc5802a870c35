//! A rectangle of pixels of the full image. The renderer picks the pixels to
//! render by it and an integrator's view bounds its samples by it, so it lives
//! below both (with the film whose pixels it names), and neither folder needs
//! the other for it.

/// A rectangle of pixels of the full image: columns `x0..x0 + width`, rows `y0..y0 + height`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelWindow {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// Columns.
    pub width: u32,
    /// Rows.
    pub height: u32,
}

impl PixelWindow {
    /// Whether the window has pixels and all of them lie in `outer`.
    pub fn is_inside(&self, outer: PixelWindow) -> bool {
        self.width > 0
            && self.height > 0
            && self.x0 >= outer.x0
            && self.y0 >= outer.y0
            && self.x0 as u64 + self.width as u64 <= outer.x0 as u64 + outer.width as u64
            && self.y0 as u64 + self.height as u64 <= outer.y0 as u64 + outer.height as u64
    }
}
