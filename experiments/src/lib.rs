//! The `grassbench` command's library half: the registry of techniques, the built-in scenes,
//! and the commands themselves (so integration tests can call them without a subprocess).

pub mod commands;
pub mod registry;
pub mod scenes;
pub mod ui;
