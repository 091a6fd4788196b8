//! `cargo xtask cluster-test [--runs N] [--keep]`: a real Slurm on localhost runs a
//! 4-shard `argus run gimpo` campaign and its merge from the job files of
//! `argus campaign plan`, and the merged `summary.json` must equal a single-process run
//! of the same runs (everything but the output paths).
//!
//! Steps: install `slurm-wlm` and `munge` from the distribution's packages if `slurmctld`
//! is absent (`apt-get install -y`, as root); in a fresh work directory, a munge key and
//! a `munged` on its own socket, a one-node `slurm.conf` for this host (the node's CPUs
//! and memory from `slurmd -C`; `ProctrackType=proctrack/linuxproc`, `TaskPlugin=task/none`,
//! `SelectType=select/cons_tres`, ports 16817/16818), `slurmctld` and `slurmd`; then the
//! 4-shard campaign, the same campaign in 1 shard, and the single-process run, each
//! timed. The daemons it started are stopped on every exit path (a guard's `Drop`).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// The ports of the test cluster (not Slurm's defaults, so a real Slurm on the machine
/// is left alone).
const CTLD_PORT: u16 = 16817;
const SLURMD_PORT: u16 = 16818;
/// How long a campaign may take on the test cluster.
const CAMPAIGN_TIMEOUT: Duration = Duration::from_secs(600);

fn run(cmd: &mut Command) -> Result<String, String> {
    let what = format!("{cmd:?}");
    let o = cmd
        .output()
        .map_err(|e| format!("cannot run {what}: {e}"))?;
    if o.status.success() {
        Ok(String::from_utf8_lossy(&o.stdout).into_owned())
    } else {
        Err(format!(
            "{what} failed ({}): {}{}",
            o.status,
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        ))
    }
}

fn have(exe: &str) -> bool {
    ["/usr/sbin", "/usr/bin", "/sbin", "/bin"]
        .iter()
        .any(|d| Path::new(d).join(exe).exists())
}

/// Installs Slurm and munge from the distribution's packages when `slurmctld` is absent.
fn install() -> Result<(), String> {
    if have("slurmctld") && have("slurmd") && have("munged") && have("sbatch") {
        eprintln!("xtask: slurm-wlm and munge are installed");
        return Ok(());
    }
    eprintln!("xtask: apt-get install -y slurm-wlm munge");
    let install = || {
        run(Command::new("apt-get")
            .args(["install", "-y", "slurm-wlm", "munge"])
            .env("DEBIAN_FRONTEND", "noninteractive"))
    };
    if install().is_err() {
        run(Command::new("apt-get").arg("update"))?;
        install()?;
    }
    Ok(())
}

/// The daemons started, stopped when dropped (in reverse order of start).
struct Daemons {
    dir: PathBuf,
    conf: PathBuf,
    /// Pid files of the daemons started, in start order.
    pid_files: Vec<(&'static str, PathBuf)>,
}

impl Daemons {
    fn pid(file: &Path) -> Option<u32> {
        std::fs::read_to_string(file).ok()?.trim().parse().ok()
    }

    fn alive(pid: u32) -> bool {
        // A zombie (exited, not yet reaped by its parent) counts as stopped.
        std::fs::read_to_string(format!("/proc/{pid}/stat"))
            .map(|s| {
                !s.rsplit(')')
                    .next()
                    .unwrap_or("")
                    .trim_start()
                    .starts_with('Z')
            })
            .unwrap_or(false)
    }
}

impl Drop for Daemons {
    fn drop(&mut self) {
        // Ask slurmctld to stop itself and every slurmd, then TERM what is left, by pid.
        let _ = Command::new("scontrol")
            .arg("shutdown")
            .env("SLURM_CONF", &self.conf)
            .output();
        for (name, file) in self.pid_files.iter().rev() {
            let Some(pid) = Self::pid(file) else {
                eprintln!("xtask: {name} stopped (its pid file is gone)");
                continue;
            };
            let deadline = Instant::now() + Duration::from_secs(10);
            let mut termed = false;
            while Self::alive(pid) && Instant::now() < deadline {
                if !termed
                    && (*name == "munged" || Instant::now() + Duration::from_secs(7) > deadline)
                {
                    let _ = Command::new("kill").arg(pid.to_string()).output();
                    termed = true;
                }
                std::thread::sleep(Duration::from_millis(200));
            }
            if Self::alive(pid) {
                let _ = Command::new("kill")
                    .args(["-KILL", &pid.to_string()])
                    .output();
            }
            eprintln!("xtask: stopped {name} (pid {pid})");
        }
        eprintln!("xtask: test cluster files in {}", self.dir.display());
    }
}

/// The `NodeName=… CPUs=… RealMemory=…` line of `slurmd -C`, with the node's address.
fn node_line() -> Result<(String, String), String> {
    let c = run(Command::new("slurmd").arg("-C"))?;
    let line = c
        .lines()
        .find(|l| l.starts_with("NodeName="))
        .ok_or_else(|| format!("slurmd -C printed no NodeName line: {c}"))?;
    let name = line
        .split_whitespace()
        .next()
        .and_then(|w| w.strip_prefix("NodeName="))
        .unwrap_or("localhost")
        .to_owned();
    let rest: Vec<&str> = line.split_whitespace().skip(1).collect();
    Ok((
        name.clone(),
        format!(
            "NodeName={name} NodeAddr=127.0.0.1 {} State=UNKNOWN",
            rest.join(" ")
        ),
    ))
}

fn slurm_conf(dir: &Path, node: &str, node_line: &str) -> String {
    let d = dir.display();
    format!(
        "# One-node test cluster of `cargo xtask cluster-test`.\n\
         ClusterName=arguscitest\n\
         SlurmctldHost={node}(127.0.0.1)\n\
         SlurmUser=root\n\
         SlurmdUser=root\n\
         AuthType=auth/munge\n\
         CredType=cred/munge\n\
         AuthInfo=socket={d}/munge.socket\n\
         StateSaveLocation={d}/state\n\
         SlurmdSpoolDir={d}/spool\n\
         SlurmctldPidFile={d}/slurmctld.pid\n\
         SlurmdPidFile={d}/slurmd.pid\n\
         SlurmctldLogFile={d}/slurmctld.log\n\
         SlurmdLogFile={d}/slurmd.log\n\
         SlurmctldPort={CTLD_PORT}\n\
         SlurmdPort={SLURMD_PORT}\n\
         ProctrackType=proctrack/linuxproc\n\
         TaskPlugin=task/none\n\
         SelectType=select/cons_tres\n\
         SelectTypeParameters=CR_Core\n\
         SchedulerType=sched/backfill\n\
         JobCompType=jobcomp/none\n\
         AccountingStorageType=accounting_storage/none\n\
         JobAcctGatherType=jobacct_gather/none\n\
         MpiDefault=none\n\
         ReturnToService=2\n\
         {node_line}\n\
         PartitionName=debug Nodes={node} Default=YES MaxTime=INFINITE State=UP\n"
    )
}

fn log_tail(file: &Path) -> String {
    let text = std::fs::read_to_string(file).unwrap_or_default();
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(15)..].join("\n")
}

/// Starts munged, slurmctld and slurmd in `dir` and waits for the node to be idle.
fn start(dir: &Path) -> Result<Daemons, String> {
    for sub in ["state", "spool"] {
        std::fs::create_dir_all(dir.join(sub)).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    let (node, line) = node_line()?;
    let conf = dir.join("slurm.conf");
    std::fs::write(&conf, slurm_conf(dir, &node, &line)).map_err(|e| e.to_string())?;
    let mut daemons = Daemons {
        dir: dir.to_path_buf(),
        conf: conf.clone(),
        pid_files: Vec::new(),
    };
    // munge: a key of our own, read by a munged on its own socket.
    let key = dir.join("munge.key");
    run(Command::new("dd")
        .args(["if=/dev/urandom", "bs=1024", "count=1"])
        .arg(format!("of={}", key.display())))?;
    run(Command::new("chmod").arg("0400").arg(&key))?;
    let p = |f: &str| dir.join(f).display().to_string();
    run(Command::new("munged").args([
        "--force",
        &format!("--socket={}", p("munge.socket")),
        &format!("--pid-file={}", p("munged.pid")),
        &format!("--log-file={}", p("munged.log")),
        &format!("--seed-file={}", p("munged.seed")),
        &format!("--key-file={}", key.display()),
    ]))
    .map_err(|e| format!("{e}\nmunged.log:\n{}", log_tail(&dir.join("munged.log"))))?;
    daemons.pid_files.push(("munged", dir.join("munged.pid")));
    run(Command::new("slurmctld").arg("-f").arg(&conf)).map_err(|e| {
        format!(
            "{e}\nslurmctld.log:\n{}",
            log_tail(&dir.join("slurmctld.log"))
        )
    })?;
    daemons
        .pid_files
        .push(("slurmctld", dir.join("slurmctld.pid")));
    run(Command::new("slurmd").arg("-f").arg(&conf))
        .map_err(|e| format!("{e}\nslurmd.log:\n{}", log_tail(&dir.join("slurmd.log"))))?;
    daemons.pid_files.push(("slurmd", dir.join("slurmd.pid")));
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        let state = Command::new("sinfo")
            .args(["-h", "-o", "%T"])
            .env("SLURM_CONF", &conf)
            .output()
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_owned())
            .unwrap_or_default();
        if state == "idle" {
            break;
        }
        if Instant::now() > deadline {
            return Err(format!(
                "the node is '{state}', not idle, after 60 s\nslurmctld.log:\n{}\nslurmd.log:\n{}",
                log_tail(&dir.join("slurmctld.log")),
                log_tail(&dir.join("slurmd.log"))
            ));
        }
        std::thread::sleep(Duration::from_millis(500));
    }
    eprintln!("xtask: one-node Slurm up ({line})");
    Ok(daemons)
}

/// A job's state (`COMPLETED`, `PENDING` …) and its reason.
fn job_state(conf: &Path, job: &str) -> (String, String) {
    let out = Command::new("scontrol")
        .args(["show", "job", job])
        .env("SLURM_CONF", conf)
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).into_owned())
        .unwrap_or_default();
    let field = |k: &str| {
        out.split_whitespace()
            .find_map(|w| w.strip_prefix(k))
            .unwrap_or("")
            .to_owned()
    };
    (field("JobState="), field("Reason="))
}

/// Plans and submits a campaign of `shards` shards, waits for its merge; returns the wall
/// time from submission to the merge's completion and the merged directory.
fn campaign(
    argus: &Path,
    conf: &Path,
    dir: &Path,
    runs: u64,
    shards: u64,
) -> Result<(Duration, PathBuf), String> {
    let plan = dir.join(format!("plan-{shards}"));
    let shared = dir.join(format!("shared-{shards}"));
    run(Command::new(argus)
        .args(["campaign", "plan", "gimpo", "--runs"])
        .arg(format!("0..{runs}"))
        .args(["--shards", &shards.to_string(), "--seed", "7", "--out"])
        .arg(&plan)
        .arg("--shared")
        .arg(&shared)
        .arg("--argus")
        .arg(argus))?;
    let started = Instant::now();
    run(Command::new("bash")
        .arg(plan.join("submit.sh"))
        .env("SLURM_CONF", conf))?;
    let jobs = std::fs::read_to_string(plan.join(".jobs")).map_err(|e| e.to_string())?;
    let merge = jobs.split_whitespace().nth(1).unwrap_or("").to_owned();
    loop {
        let (state, reason) = job_state(conf, &merge);
        match state.as_str() {
            "COMPLETED" => break,
            "FAILED" | "CANCELLED" | "TIMEOUT" | "NODE_FAIL" | "OUT_OF_MEMORY" | "BOOT_FAIL" => {
                return Err(format!(
                    "merge job {merge}: {state} ({reason}); logs in {}",
                    shared.join("logs").display()
                ));
            }
            _ if reason.contains("DependencyNeverSatisfied") => {
                return Err(format!(
                    "a shard failed (merge job {merge}: {reason}); logs in {}",
                    shared.join("logs").display()
                ));
            }
            _ => {}
        }
        if started.elapsed() > CAMPAIGN_TIMEOUT {
            return Err(format!(
                "campaign of {shards} shards not done after {CAMPAIGN_TIMEOUT:?} (merge {merge}: {state} {reason})"
            ));
        }
        std::thread::sleep(Duration::from_millis(200));
    }
    Ok((started.elapsed(), shared.join("merged")))
}

/// `summary.json` of `dir` without its `files` (the output paths).
fn summary(dir: &Path) -> Result<serde_json::Value, String> {
    let f = dir.join("summary.json");
    let text = std::fs::read_to_string(&f).map_err(|e| format!("{}: {e}", f.display()))?;
    let mut v: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", f.display()))?;
    if let Some(o) = v.as_object_mut() {
        o.remove("files");
    }
    Ok(v)
}

/// The command: see the module docs.
pub(crate) fn cluster_test(root: &Path, args: &[String]) -> Result<(), String> {
    let runs: u64 = match args.iter().position(|a| a == "--runs") {
        Some(i) => args
            .get(i + 1)
            .and_then(|v| v.parse().ok())
            .ok_or("--runs takes a run count")?,
        None => 200,
    };
    let total = Instant::now();
    install()?;
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned());
    run(Command::new(&cargo)
        .args(["build", "-p", "argus-cli"])
        .current_dir(root))?;
    let target =
        std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| root.join("target"), PathBuf::from);
    let argus =
        std::path::absolute(target.join("debug").join("argus")).map_err(|e| e.to_string())?;
    let dir = std::env::temp_dir().join(format!("argus-cluster-test-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let daemons = start(&dir)?;
    let conf = daemons.conf.clone();

    let (t4, merged4) = campaign(&argus, &conf, &dir, runs, 4)?;
    eprintln!("xtask: 4 shards: {:.1} s", t4.as_secs_f64());
    let (t1, merged1) = campaign(&argus, &conf, &dir, runs, 1)?;
    eprintln!("xtask: 1 shard: {:.1} s", t1.as_secs_f64());
    drop(daemons);

    let whole = dir.join("whole");
    let started = Instant::now();
    run(Command::new(&argus)
        .args(["run", "gimpo", "--seed", "7", "--runs"])
        .arg(format!("0..{runs}"))
        .arg("--out")
        .arg(&whole))?;
    let t0 = started.elapsed();
    let want = summary(&whole)?;
    for (name, m) in [("4 shards", &merged4), ("1 shard", &merged1)] {
        if summary(m)? != want {
            return Err(format!(
                "the merged summary.json of {name} ({}) differs from the single-process run's ({})",
                m.display(),
                whole.display()
            ));
        }
    }
    let cpus = std::thread::available_parallelism().map_or(1, std::num::NonZero::get);
    let report = format!(
        "cluster-test: gimpo, {runs} runs, seed 7, one-node Slurm on {cpus} CPUs (1 CPU per task)\n\
         4 shards (job array + afterok merge): {:.1} s wall, submission to merged report\n\
         1 shard  (job array + afterok merge): {:.1} s wall\n\
         single process (argus run, {cpus} threads): {:.1} s wall\n\
         merged summary.json of both campaigns == the single-process run's (all but output paths)\n\
         total {:.0} s\n",
        t4.as_secs_f64(),
        t1.as_secs_f64(),
        t0.as_secs_f64(),
        total.elapsed().as_secs_f64()
    );
    print!("{report}");
    std::fs::write(dir.join("timings.txt"), &report).map_err(|e| e.to_string())?;
    if !args.iter().any(|a| a == "--keep") {
        let _ = std::fs::remove_dir_all(&dir);
    }
    Ok(())
}
