//! Built-in types (atomic, the predefined records, non-value types, aliases) and predefined
//! data that are not written in RAPID (`ERR_*`, `pi`, `AIO_*`, mechanical units, signals).

use crate::ir::{Field, Ty, TypeId, TypeKind, TypeTable};

/// Value records: (name, [(component, type)]).
const RECORDS: &[(&str, &[(&str, &str)])] = &[
    ("pos", &[("x", "num"), ("y", "num"), ("z", "num")]),
    (
        "orient",
        &[("q1", "num"), ("q2", "num"), ("q3", "num"), ("q4", "num")],
    ),
    ("pose", &[("trans", "pos"), ("rot", "orient")]),
    (
        "confdata",
        &[
            ("cf1", "num"),
            ("cf4", "num"),
            ("cf6", "num"),
            ("cfx", "num"),
        ],
    ),
    (
        "robjoint",
        &[
            ("rax_1", "num"),
            ("rax_2", "num"),
            ("rax_3", "num"),
            ("rax_4", "num"),
            ("rax_5", "num"),
            ("rax_6", "num"),
        ],
    ),
    (
        "extjoint",
        &[
            ("eax_a", "num"),
            ("eax_b", "num"),
            ("eax_c", "num"),
            ("eax_d", "num"),
            ("eax_e", "num"),
            ("eax_f", "num"),
        ],
    ),
    // The program displacement and external-axis offsets in force (`C_PROGDISP`).
    ("progdisp", &[("pdisp", "pose"), ("eoffs", "extjoint")]),
    (
        "robtarget",
        &[
            ("trans", "pos"),
            ("rot", "orient"),
            ("robconf", "confdata"),
            ("extax", "extjoint"),
        ],
    ),
    (
        "jointtarget",
        &[("robax", "robjoint"), ("extax", "extjoint")],
    ),
    (
        "loaddata",
        &[
            ("mass", "num"),
            ("cog", "pos"),
            ("aom", "orient"),
            ("ix", "num"),
            ("iy", "num"),
            ("iz", "num"),
        ],
    ),
    (
        "tooldata",
        &[
            ("robhold", "bool"),
            ("tframe", "pose"),
            ("tload", "loaddata"),
        ],
    ),
    (
        "wobjdata",
        &[
            ("robhold", "bool"),
            ("ufprog", "bool"),
            ("ufmec", "string"),
            ("uframe", "pose"),
            ("oframe", "pose"),
        ],
    ),
    (
        "speeddata",
        &[
            ("v_tcp", "num"),
            ("v_ori", "num"),
            ("v_leax", "num"),
            ("v_reax", "num"),
        ],
    ),
    (
        "zonedata",
        &[
            ("finep", "bool"),
            ("pzone_tcp", "num"),
            ("pzone_ori", "num"),
            ("pzone_eax", "num"),
            ("zone_ori", "num"),
            ("zone_leax", "num"),
            ("zone_reax", "num"),
        ],
    ),
    ("egm_minmax", &[("min", "num"), ("max", "num")]),
    ("listitem", &[("image", "string"), ("text", "string")]),
    // Several tasks: a task list entry and a RAPID message's header.
    ("tasks", &[("taskname", "string")]),
    (
        "rmqheader",
        &[
            ("datatype", "string"),
            ("ndim", "num"),
            ("dim1", "num"),
            ("dim2", "num"),
            ("dim3", "num"),
        ],
    ),
];

/// Non-value and semi-value types, modelled as records with hidden components.
const OPAQUE: &[(&str, &[(&str, &str)])] = &[
    (
        "clock",
        &[("running", "bool"), ("started", "dnum"), ("acc", "dnum")],
    ),
    ("egmident", &[("id", "num")]),
    // A correction generator (`CorrCon`): its number, 0 when not connected.
    ("corrdescr", &[("id", "num")]),
    ("mecunit", &[("name", "string")]),
    ("signaldi", &[("name", "string")]),
    ("signaldo", &[("name", "string")]),
    ("signalai", &[("name", "string")]),
    ("signalao", &[("name", "string")]),
    ("signalgi", &[("name", "string")]),
    ("signalgo", &[("name", "string")]),
    ("socketdev", &[("id", "num")]),
    // Up to 1024 bytes and the count of valid ones; the bytes are kept as the characters
    // U+0000–U+00FF of a string (`functions::raw_bytes`).
    ("rawbytes", &[("len", "num"), ("bytes", "string")]),
    ("iodev", &[("id", "num")]),
    // A position event (`interp/builtins/motion_events/trigg.rs`).
    (
        "triggdata",
        &[
            ("kind", "num"),
            ("distance", "num"),
            ("start", "bool"),
            ("time", "bool"),
            ("lead", "num"),
            ("signal", "string"),
            ("value", "dnum"),
            ("intno", "num"),
        ],
    ),
    // Several tasks: a synchronisation point (named by its variable), an RMQ client, and a
    // RAPID message (header, data as literal text, sender, \UserDef, valid).
    ("syncident", &[("id", "num")]),
    ("rmqslot", &[("slot", "num")]),
    (
        "rmqmessage",
        &[
            ("datatype", "string"),
            ("ndim", "num"),
            ("dim1", "num"),
            ("dim2", "num"),
            ("dim3", "num"),
            ("data", "string"),
            ("sender", "num"),
            ("userdef", "num"),
            ("valid", "bool"),
        ],
    ),
    ("dir", &[("id", "num")]),
    // A load session of `StartLoad`/`WaitLoad` and a block of `GetNextSym`/`SetDataVal`.
    ("loadsession", &[("id", "num")]),
    ("datapos", &[("id", "num")]),
    (
        "trapdata",
        &[
            ("domain", "num"),
            ("number", "num"),
            ("type", "num"),
            ("title", "string"),
            ("str1", "string"),
            ("str2", "string"),
            ("str3", "string"),
            ("str4", "string"),
            ("str5", "string"),
        ],
    ),
];

/// Aliases of `num` known to the kernel, sockets and the EGM option.
const NUM_ALIASES: &[&str] = &[
    "errnum",
    "intnum",
    "dionum",
    "byte",
    "btnres",
    "errdomain",
    "errtype",
    "identno",
    "aiotrigg",
    "buttondata",
    "icondata",
    "tpnum",
    "egmstate",
    "egmstopmode",
    "egmframetype",
    "egmcorrstate",
    "socketstatus",
    "inttypes",
];

/// `aiotrigg` constants (ISignalAO conditions).
pub const AIO_CONSTS: &[(&str, f64)] = &[
    ("AIO_ABOVE_HIGH", 1.0),
    ("AIO_BELOW_HIGH", 2.0),
    ("AIO_ABOVE_LOW", 3.0),
    ("AIO_BELOW_LOW", 4.0),
    ("AIO_BETWEEN", 5.0),
    ("AIO_OUTSIDE", 6.0),
    ("AIO_ALWAYS", 7.0),
];

/// The type table with every built-in type.
pub fn builtin_types() -> TypeTable {
    let mut t = TypeTable::new();
    for (name, fields) in RECORDS {
        add_record(&mut t, name, fields, true);
    }
    for (name, fields) in OPAQUE {
        add_record(&mut t, name, fields, false);
    }
    for name in NUM_ALIASES {
        t.add(name, TypeKind::Alias(TypeId::NUM), false);
    }
    t
}

fn add_record(t: &mut TypeTable, name: &str, fields: &[(&str, &str)], value: bool) {
    let fields = fields
        .iter()
        .map(|(f, ty)| Field {
            name: f.to_string(),
            ty: Ty::scalar(t.lookup(ty).map(|id| t.resolve(id)).unwrap_or(TypeId::NUM)),
            dims: Vec::new(),
        })
        .collect();
    t.add(name, TypeKind::Record { fields, value }, false);
}
