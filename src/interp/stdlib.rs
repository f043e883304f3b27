//! The embedded stdlib: RAPID system modules with the predefined data (`stdlib/*.sys`),
//! loaded before the user's modules. Natives and built-in types live in `builtins` and
//! `sema`; the two halves meet in the program loader.

/// (display name, text) of every stdlib module, in load order.
pub const SOURCES: &[(&str, &str)] = &[
    ("<stdlib>/base.sys", include_str!("../../stdlib/base.sys")),
    ("<stdlib>/speed.sys", include_str!("../../stdlib/speed.sys")),
    ("<stdlib>/zone.sys", include_str!("../../stdlib/zone.sys")),
    ("<stdlib>/egm.sys", include_str!("../../stdlib/egm.sys")),
    ("<stdlib>/misc.sys", include_str!("../../stdlib/misc.sys")),
    (
        "<stdlib>/system.sys",
        include_str!("../../stdlib/system.sys"),
    ),
    ("<stdlib>/files.sys", include_str!("../../stdlib/files.sys")),
    (
        "<stdlib>/socket.sys",
        include_str!("../../stdlib/socket.sys"),
    ),
    ("<stdlib>/ui.sys", include_str!("../../stdlib/ui.sys")),
];

/// The controller's default USER system module (`reg1` … `reg5`, `clock1`): loaded with the
/// user's modules (its data are ordinary variables) unless they have a module USER.
pub const DEFAULT_USER: (&str, &str) = ("<stdlib>/user.sys", include_str!("../../stdlib/user.sys"));
