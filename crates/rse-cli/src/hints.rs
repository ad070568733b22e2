//! What to do about an error, in the command line's words: the libraries'
//! messages say what is wrong without naming flags (Python users pass
//! keywords), and the command line adds the flag that fixes it.

/// The flag that fixes `error`, when there is one.
pub fn hint(error: &anyhow::Error) -> Option<&'static str> {
    error.chain().find_map(|cause| {
        if let Some(e) = cause.downcast_ref::<rse_world::Error>() {
            return match e {
                rse_world::Error::Conflict { .. } => Some("rerun with --force to replace it"),
                rse_world::Error::Core(core) => core_hint(core),
                _ => None,
            };
        }
        cause.downcast_ref::<rse_core::Error>().and_then(core_hint)
    })
}

fn core_hint(error: &rse_core::Error) -> Option<&'static str> {
    match error {
        rse_core::Error::PreviewTooLarge { .. } => Some("use fewer --cell-pixels"),
        rse_core::Error::SheetTooLarge { .. } => Some("use fewer --cols or --cell-pixels"),
        _ => None,
    }
}

/// Whether `error` is a closed pipe (`rse-gen heightmap … | head`).
pub fn is_broken_pipe(error: &anyhow::Error) -> bool {
    error.chain().any(|cause| {
        cause
            .downcast_ref::<std::io::Error>()
            .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
    })
}
