//! A test tool for the cross-check with an independent ASTERIX decoder:
//!
//! - `asterix_json samples OUT` writes the Argus-written samples of every
//!   category (`argus_asterix::samples::all_categories`) as a raw block file;
//! - `asterix_json decode FILE` prints, as JSON, every record Argus decodes
//!   from a raw block file, item by item, with the fields named and scaled as
//!   the wire's physical units (NM, degrees, FL, seconds, knots, m, m/s;
//!   Mode-3/A as four octal digits, addresses as six hex digits), and every
//!   skip with its reason, byte offset and item.
#![allow(missing_docs)]

use std::process::ExitCode;

use argus_asterix::{
    Cat021, Cat034, Cat048, Cat062, DecodeError, NM, Record, Skip, TimeOfDay, decode, samples,
};
use serde_json::{Map, Value, json};

fn tod(t: TimeOfDay) -> Value {
    json!(t.seconds())
}

fn cat048(r: &Cat048) -> Map<String, Value> {
    let mut m = Map::new();
    if let Some(s) = r.source {
        m.insert("I010".into(), json!({"SAC": s.sac, "SIC": s.sic}));
    }
    if let Some(t) = r.time {
        m.insert("I140".into(), json!({"ToD": tod(t)}));
    }
    if let Some(d) = r.descriptor {
        let mut f = json!({"TYP": d.typ, "SIM": u8::from(d.sim), "RDP": u8::from(d.rdp),
            "SPI": u8::from(d.spi), "RAB": u8::from(d.rab)});
        if let Some(e) = d.extension {
            // Edition 1.21 first extension: TST, (spare/ERR), XPP, ME, MI, FOE/FRI.
            f["TST"] = json!(e >> 7);
            f["XPP"] = json!((e >> 5) & 1);
            f["ME"] = json!((e >> 4) & 1);
            f["MI"] = json!((e >> 3) & 1);
            f["FOEFRI"] = json!((e >> 1) & 3);
        }
        m.insert("I020".into(), f);
    }
    if let Some(p) = r.polar {
        m.insert(
            "I040".into(),
            json!({"RHO": p.range_m() / NM, "THETA": p.theta.degrees()}),
        );
    }
    if let Some(c) = r.mode3a {
        m.insert(
            "I070".into(),
            json!({"V": u8::from(c.not_validated), "G": u8::from(c.garbled),
                "L": u8::from(c.not_extracted), "Mode3A": format!("{:04o}", c.code)}),
        );
    }
    if let Some(f) = r.flight_level {
        m.insert(
            "I090".into(),
            json!({"V": u8::from(f.not_validated), "G": u8::from(f.garbled), "FL": f.flight_level()}),
        );
    }
    if let Some(a) = r.aircraft_address {
        m.insert("I220".into(), json!({"ACAddr": format!("{a:06X}")}));
    }
    if let Some(n) = r.track_number {
        m.insert("I161".into(), json!({"Tn": n}));
    }
    if let Some(c) = r.cartesian {
        let (x, y) = c.metres();
        m.insert("I042".into(), json!({"X": x / NM, "Y": y / NM}));
    }
    if let Some(v) = r.velocity {
        // Knots: m/s × 3600 / 1852.
        m.insert(
            "I200".into(),
            json!({"CGS": v.speed_mps() * 3600.0 / NM, "CHdg": v.heading.degrees()}),
        );
    }
    if let Some(s) = r.track_status {
        let mut f = json!({"CNF": u8::from(s.tentative), "RAD": s.rad, "DOU": u8::from(s.doubtful),
            "MAH": u8::from(s.manoeuvre), "CDM": s.cdm});
        if let Some(e) = s.extension {
            f["TRE"] = json!(e >> 7);
            f["GHO"] = json!((e >> 6) & 1);
            f["SUP"] = json!((e >> 5) & 1);
            f["TCC"] = json!((e >> 4) & 1);
        }
        m.insert("I170".into(), f);
    }
    m
}

fn cat034(r: &Cat034) -> Map<String, Value> {
    let mut m = Map::new();
    if let Some(s) = r.source {
        m.insert("I010".into(), json!({"SAC": s.sac, "SIC": s.sic}));
    }
    if let Some(t) = r.message_type {
        m.insert("I000".into(), json!({"MsgTyp": t.code()}));
    }
    if let Some(t) = r.time {
        m.insert("I030".into(), json!({"ToD": tod(t)}));
    }
    if let Some(s) = r.sector {
        m.insert("I020".into(), json!({"Azi": s.degrees()}));
    }
    if let Some(p) = r.rotation_period {
        m.insert("I041".into(), json!({"RotS": p.seconds()}));
    }
    m
}

fn cat021(r: &Cat021) -> Map<String, Value> {
    let mut m = Map::new();
    let mut time = |item: &str, field: &str, t: Option<TimeOfDay>| {
        if let Some(t) = t {
            m.insert(item.into(), json!({ field: tod(t) }));
        }
    };
    time("I071", "time_applicability_position", r.t_position);
    time("I072", "time_applicability_velocity", r.t_velocity);
    time("I073", "time_reception_position", r.t_rx_position);
    time("I075", "time_reception_velocity", r.t_rx_velocity);
    time("I077", "time_report_transmission", r.t_report);
    if let Some(s) = r.source {
        m.insert("I010".into(), json!({"SAC": s.sac, "SIC": s.sic}));
    }
    if let Some(p) = r.position {
        m.insert("I130".into(), json!({"Lat": p.lat_deg, "Lon": p.lon_deg}));
    }
    if let Some(p) = r.position_hr {
        m.insert("I131".into(), json!({"Lat": p.lat_deg, "Lon": p.lon_deg}));
    }
    if let Some(a) = r.target_address {
        m.insert("I080".into(), json!({"TAddr": format!("{a:06X}")}));
    }
    if let Some(q) = r.quality {
        let mut f = json!({"NUCr_or_NACv": q.nac_v, "NUCp_or_NIC": q.nic});
        if let Some(e) = q.extension {
            f["NICbaro"] = json!(u8::from(e.nic_baro));
            f["SIL"] = json!(e.sil);
            f["NACp"] = json!(e.nac_p);
        }
        m.insert("I090".into(), f);
    }
    m
}

fn cat062(r: &Cat062) -> Map<String, Value> {
    let mut m = Map::new();
    if let Some(s) = r.source {
        m.insert("I010".into(), json!({"SAC": s.sac, "SIC": s.sic}));
    }
    if let Some(t) = r.time {
        m.insert("I070".into(), json!({"ToT": tod(t)}));
    }
    if let Some(p) = r.wgs84 {
        let (lat, lon) = p.degrees();
        m.insert("I105".into(), json!({"Lat": lat, "Lon": lon}));
    }
    if let Some(c) = r.cartesian {
        let (x, y) = c.metres();
        m.insert("I100".into(), json!({"X": x, "Y": y}));
    }
    if let Some(v) = r.velocity {
        let (vx, vy) = v.mps();
        m.insert("I185".into(), json!({"Vx": vx, "Vy": vy}));
    }
    if let Some(n) = r.track_number {
        m.insert("I040".into(), json!({"TrkN": n}));
    }
    m
}

fn record(r: &Record) -> Value {
    let (cat, items) = match r {
        Record::Cat048(r) => (48, cat048(r)),
        Record::Cat034(r) => (34, cat034(r)),
        Record::Cat021(r) => (21, cat021(r)),
        Record::Cat062(r) => (62, cat062(r)),
        _ => (0, Map::new()),
    };
    json!({"category": cat, "items": items})
}

fn skip(s: &Skip) -> Value {
    let e: &DecodeError = &s.error;
    json!({"reason": e.reason(), "offset": e.offset(), "item": e.item().map(|i| i.to_string()),
        "dropped": s.dropped, "message": e.to_string()})
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.as_slice() {
        [cmd, out] if cmd == "samples" => samples::all_categories()
            .map_err(|e| e.to_string())
            .and_then(|b| std::fs::write(out, b).map_err(|e| format!("{out}: {e}"))),
        [cmd, input] if cmd == "decode" => std::fs::read(input)
            .map_err(|e| format!("{input}: {e}"))
            .map(|bytes| {
                let d = decode(&bytes);
                let out = json!({
                    "records": d.records.iter().map(record).collect::<Vec<_>>(),
                    "skipped": d.skipped.iter().map(skip).collect::<Vec<_>>(),
                });
                println!("{out}");
            }),
        _ => Err("usage: asterix_json samples OUT | decode FILE".to_owned()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("asterix_json: {e}");
            ExitCode::FAILURE
        }
    }
}
