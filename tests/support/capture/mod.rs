//! An in-memory writer that a ratatui backend writes into and the test reads back (stock
//! backends do not hand their writer back on stable ratatui).

use std::cell::RefCell;
use std::io::Write;
use std::rc::Rc;

/// A shared byte buffer: clone it into the backend, keep one to read.
#[derive(Clone, Default)]
pub struct Capture(pub Rc<RefCell<Vec<u8>>>);

impl Write for Capture {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0.borrow_mut().extend_from_slice(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

impl Capture {
    /// Everything written since the last take.
    #[allow(dead_code)] // not every test file takes
    pub fn take(&self) -> Vec<u8> {
        std::mem::take(&mut self.0.borrow_mut())
    }
}
