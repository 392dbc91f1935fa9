//! The emulated PLEN2's motion memory: a slot is a header and up to 20
//! frames, read by the motion controller as the firmware reads its EEPROM.

use crate::protocol::plen2::playback::MotionStore;
use crate::protocol::plen2::{MAX_FRAMES, MotionFrame, MotionHeader};

/// One slot as stored.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct Slot {
    pub(super) header: MotionHeader,
    pub(super) frames: [Option<MotionFrame>; MAX_FRAMES],
}

/// The slots as the motion controller reads them.
pub(super) struct Eeprom<'a>(pub(super) &'a [Option<Slot>]);

impl MotionStore for Eeprom<'_> {
    fn header(&self, slot: u8) -> Option<MotionHeader> {
        let header = &self.0.get(usize::from(slot))?.as_ref()?.header;
        // The firmware drops a header whose frame count is not 1..=20.
        (1..=MAX_FRAMES).contains(&usize::from(header.frame_count)).then(|| header.clone())
    }

    fn frame(&self, slot: u8, index: u8) -> Option<MotionFrame> {
        self.0.get(usize::from(slot))?.as_ref()?.frames.get(usize::from(index))?.clone()
    }
}
