//! The key map: which key does what in the window.

use winit::keyboard::{Key, NamedKey};

/// What a key asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    /// Space: start or stop the swing.
    TogglePause,
    /// R: back to the asset's initial state.
    Reset,
    /// Left / Right: one ball fewer / more lifted.
    Lift(i32),
    /// Down / Up: one ball fewer / more.
    Balls(i32),
    /// H or F1: status HUD -> status and help -> nothing -> status.
    ToggleHud,
    /// S: save a screenshot.
    Screenshot,
    /// V: save the last 10 seconds as an animated PNG (and WAV).
    Replay,
    /// `,` / `.`: half / twice the time rate (1/16x..=4x).
    Rate(i32),
    /// N: one frame (1/60 s of simulated time, at the rate) while paused.
    Step,
    /// C: back to the asset's view.
    HomeView,
    /// Tab: the control panel on or off.
    Panel,
    /// Ctrl+Z: undo the last change made in the panel (a preset included).
    Undo,
    /// M: mute or unmute the clicks.
    Mute,
    /// G: the graphs window on or off.
    Graphs,
    /// Shift+G: the graphs' series as CSV.
    GraphsCsv,
    /// Escape: quit.
    Quit,
}

/// The action of a pressed key, with Ctrl and Shift held or not, if it has one.
#[must_use]
pub fn action(key: &Key, ctrl: bool, shift: bool) -> Option<Action> {
    if ctrl {
        return match key {
            Key::Character(c) if c.eq_ignore_ascii_case("z") => Some(Action::Undo),
            _ => None,
        };
    }
    match key {
        Key::Named(NamedKey::Space) => Some(Action::TogglePause),
        Key::Named(NamedKey::ArrowLeft) => Some(Action::Lift(-1)),
        Key::Named(NamedKey::ArrowRight) => Some(Action::Lift(1)),
        Key::Named(NamedKey::ArrowDown) => Some(Action::Balls(-1)),
        Key::Named(NamedKey::ArrowUp) => Some(Action::Balls(1)),
        Key::Named(NamedKey::F1) => Some(Action::ToggleHud),
        Key::Named(NamedKey::Tab) => Some(Action::Panel),
        Key::Named(NamedKey::Escape) => Some(Action::Quit),
        Key::Character(c) => match c.to_lowercase().as_str() {
            "r" => Some(Action::Reset),
            "h" => Some(Action::ToggleHud),
            "s" => Some(Action::Screenshot),
            "v" => Some(Action::Replay),
            "," => Some(Action::Rate(-1)),
            "." => Some(Action::Rate(1)),
            "n" => Some(Action::Step),
            "c" => Some(Action::HomeView),
            "m" => Some(Action::Mute),
            "g" if shift => Some(Action::GraphsCsv),
            "g" => Some(Action::Graphs),
            " " => Some(Action::TogglePause),
            _ => None,
        },
        _ => None,
    }
}

/// The help the HUD shows: every key and mouse action, as (keys, what).
pub const HELP: [(&str, &str); 18] = [
    ("SPACE", "start / stop the swing"),
    ("left-drag", "lift a ball; let go: swing"),
    ("R", "reset cradle and time rate"),
    ("LEFT/RIGHT", "fewer / more lifted"),
    ("DOWN/UP", "fewer / more balls"),
    (", / .", "half / twice time rate"),
    ("N", "one frame while paused"),
    ("right-drag", "turn the view"),
    ("middle-drag", "move the view"),
    ("shift+right", "move the view, too"),
    ("wheel / C", "zoom / reset the view"),
    ("TAB", "control panel, presets"),
    ("CTRL+Z", "undo a panel change"),
    ("S / V", "screenshot / last 10 s"),
    ("M", "mute / unmute the clicks"),
    ("G / SHIFT+G", "graphs / graphs as CSV"),
    ("H or F1", "help / no HUD / status"),
    ("ESC", "quit (in a field: leave)"),
];

#[cfg(test)]
mod tests {
    use super::{Action, action};
    use winit::keyboard::{Key, NamedKey, SmolStr};

    #[test]
    fn every_documented_key_has_its_action() {
        let ch = |c: &str| Key::Character(SmolStr::new(c));
        let action = |k: &Key| action(k, false, false);
        assert_eq!(
            action(&Key::Named(NamedKey::Space)),
            Some(Action::TogglePause)
        );
        assert_eq!(action(&ch("r")), Some(Action::Reset));
        assert_eq!(
            action(&ch("R")),
            Some(Action::Reset),
            "with Shift or Caps Lock too"
        );
        assert_eq!(
            action(&Key::Named(NamedKey::ArrowLeft)),
            Some(Action::Lift(-1))
        );
        assert_eq!(
            action(&Key::Named(NamedKey::ArrowRight)),
            Some(Action::Lift(1))
        );
        assert_eq!(
            action(&Key::Named(NamedKey::ArrowDown)),
            Some(Action::Balls(-1))
        );
        assert_eq!(
            action(&Key::Named(NamedKey::ArrowUp)),
            Some(Action::Balls(1))
        );
        assert_eq!(action(&ch("h")), Some(Action::ToggleHud));
        assert_eq!(action(&Key::Named(NamedKey::F1)), Some(Action::ToggleHud));
        assert_eq!(action(&ch("s")), Some(Action::Screenshot));
        assert_eq!(action(&ch("v")), Some(Action::Replay));
        assert_eq!(action(&Key::Named(NamedKey::Escape)), Some(Action::Quit));
        assert_eq!(action(&ch(",")), Some(Action::Rate(-1)));
        assert_eq!(action(&ch(".")), Some(Action::Rate(1)));
        assert_eq!(action(&ch("n")), Some(Action::Step));
        assert_eq!(action(&ch("c")), Some(Action::HomeView));
        assert_eq!(action(&ch("m")), Some(Action::Mute));
        assert_eq!(action(&ch("g")), Some(Action::Graphs));
        assert_eq!(
            super::action(&ch("G"), false, true),
            Some(Action::GraphsCsv)
        );
        assert_eq!(action(&ch("x")), None);
        assert_eq!(action(&Key::Named(NamedKey::Tab)), Some(Action::Panel));
    }

    #[test]
    fn ctrl_z_undoes_and_ctrl_leaves_the_other_keys_alone() {
        let ch = |c: &str| Key::Character(SmolStr::new(c));
        assert_eq!(action(&ch("z"), true, false), Some(Action::Undo));
        assert_eq!(action(&ch("Z"), true, false), Some(Action::Undo));
        assert_eq!(action(&ch("z"), false, false), None);
        assert_eq!(action(&ch("s"), true, false), None, "Ctrl+S is not S");
    }
}
