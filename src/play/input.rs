//! What a transport passes a session from its client.

use std::future::Future;

use tokio::sync::mpsc;

use crate::ui::key_bytes::KeyEvent;

/// Input from the client, as its transport knows it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Input {
    /// Bytes as a terminal sends them: keys, escape sequences, answers to queries. Holds are
    /// inferred from auto-repeat unless the terminal speaks the kitty keyboard protocol.
    Bytes(Vec<u8>),
    /// Key presses and releases as they happened (a browser knows both): holds end exactly at
    /// release. Repeats are not sent.
    Keys(Vec<KeyEvent>),
    /// Debug this column of the 3D view (the player's view freezes, as pausing does), or stop
    /// debugging (`None`): a browser page's click on its view.
    Ray(Option<u32>),
}

/// Where a session reads its client's input from: a channel of [`Input`], or of a terminal's
/// raw bytes (each chunk is [`Input::Bytes`]).
pub trait InputSource: Send {
    /// The next input; `None` once the client has closed its side.
    fn recv(&mut self) -> impl Future<Output = Option<Input>> + Send;
}

impl InputSource for mpsc::Receiver<Input> {
    async fn recv(&mut self) -> Option<Input> {
        mpsc::Receiver::recv(self).await
    }
}

impl InputSource for mpsc::Receiver<Vec<u8>> {
    async fn recv(&mut self) -> Option<Input> {
        mpsc::Receiver::recv(self).await.map(Input::Bytes)
    }
}
