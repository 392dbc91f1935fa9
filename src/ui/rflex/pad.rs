//! The gamepad driving the base (the editor reads the gamepad: `ui::gamepad`):
//! the same teleop the command line uses (dead-man, stick, dead zone). It
//! drives only while the window lets the pad act and the Drive tab is shown;
//! STOP, losing the focus, leaving the tab and the gamepad going away each
//! stop the base, and after a halt the dead-man must be let go and pressed again.

use std::time::Instant;

use crate::gamepad::teleop::{Order, StopReason, Teleop, TeleopConfig};
use crate::gamepad::{ABS_X, ABS_Y, BTN_TL, PadState, PadUpdate};
use crate::project::rflex::DriveSettings;
use crate::ui::i18n::Strings;
use crate::ui::rflex::RflexLink;
use crate::ui::rflex::captions::RflexWords;
use crate::ui::shell::Shell;

/// The gamepad's side of the Drive panel.
#[derive(Debug, Default)]
pub struct PadDrive {
    teleop: Option<Teleop>,
    /// What the pad last showed.
    pub state: Option<PadState>,
    /// Why the base is not being driven by it (None: it is).
    pub stopped: Option<StopReason>,
}

impl PadDrive {
    /// Whether the pad is driving the base.
    pub fn driving(&self) -> bool {
        self.teleop.as_ref().is_some_and(Teleop::driving)
    }

    /// The owner stopped the base (STOP, a new link): the pad lets go and waits for a fresh press.
    pub fn halt(&mut self, shell: &mut Shell<'_>) {
        if let Some(Order::Stop(_)) = self.teleop.as_mut().and_then(Teleop::halt)
            && let Some(base) = shell.rflex_mut()
        {
            base.stop();
        }
        if self.teleop.is_some() {
            self.stopped = Some(StopReason::Halted);
        }
    }

    /// Drives the base by the pad's updates; `armed`: whether the pad may act
    /// now. Whether a change waits to be sent (the window keeps repainting).
    pub fn drive(
        &mut self,
        shell: &mut Shell<'_>,
        now: Instant,
        updates: &[(Instant, PadUpdate)],
        armed: bool,
        settings: &DriveSettings,
        accel: f64,
    ) -> bool {
        let config = TeleopConfig {
            max_speed_m_per_s: settings.max_speed_m_per_s,
            max_turn_rad_per_s: settings.max_turn_rad_per_s,
            ..TeleopConfig::default()
        };
        if !updates.is_empty() && self.teleop.is_none() {
            self.teleop = Some(Teleop::new(config));
        }
        let Some(teleop) = &mut self.teleop else { return false };
        let mut orders = Vec::new();
        let mut gone = false;
        for (at, update) in updates {
            let order = if armed {
                teleop.update(*at, update)
            } else {
                // Not allowed to act (no focus, another tab, test mode): halted,
                // and only the dead-man followed — driving again takes a press
                // made once it is allowed.
                let halted = teleop.halt();
                teleop.follow(update);
                halted
            };
            match update {
                PadUpdate::State(state) => self.state = Some(state.clone()),
                PadUpdate::Dropped => self.state = None,
                PadUpdate::Gone(_) => gone = true,
            }
            orders.extend(order);
        }
        if !armed {
            orders.extend(teleop.halt());
        }
        orders.extend(teleop.poll(now));
        let pending = teleop.poll_timeout().is_some();
        for order in orders {
            let Some(base) = shell.rflex_mut() else { break };
            match order {
                Order::Drive { speed_m_per_s, turn_rad_per_s } => {
                    self.stopped = None;
                    base.drive(speed_m_per_s, turn_rad_per_s, accel);
                }
                Order::Stop(reason) => {
                    self.stopped = Some(reason);
                    base.stop();
                }
            }
        }
        if gone {
            *self = Self::default();
        } else if !self.driving() && self.stopped.is_none() {
            self.stopped = Some(StopReason::Released);
        }
        pending
    }

    /// The gamepad's line on the Drive panel.
    pub fn ui(&self, ui: &mut egui::Ui, words: &Strings) {
        let captions = words.rflex();
        let Some(pad) = &self.state else {
            ui.add(egui::Label::new(egui::RichText::new(captions.gamepad_hint).weak()).wrap());
            return;
        };
        let state = match self.stopped {
            None => captions.pad_driving,
            Some(StopReason::Released | StopReason::Gone) => captions.pad_released,
            Some(StopReason::Centred) => captions.pad_centred,
            Some(StopReason::Dropped) => captions.pad_dropped,
            Some(StopReason::Halted) => captions.pad_halted,
        };
        ui.monospace(format!(
            "{} BTN_TL {}  stick x {:+.2} y {:+.2}  — {state}",
            words.gamepad,
            if pad.pressed(BTN_TL) { "■" } else { "□" },
            pad.axis(ABS_X),
            pad.axis(ABS_Y)
        ));
    }
}
