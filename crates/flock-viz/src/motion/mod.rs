//! The whole run in motion: an animated GIF and a self-contained HTML player.

pub mod animation;
pub mod player;
