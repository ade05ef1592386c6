//! The command line (docs/contracts.md): the clap schema ([`args`]), the common
//! overrides applied to a config ([`overrides`]), and the typed [`Job`] that the
//! two become after every check ([`job`]).

pub mod args;
pub mod job;
pub mod overrides;

pub use args::{Cli, Common};
pub use job::Job;
pub use overrides::InputError;
