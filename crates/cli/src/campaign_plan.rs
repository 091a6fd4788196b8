//! `argus campaign plan`: the job files of a campaign split into K shards, for the two
//! schedulers users have (docs/cluster.md):
//!
//! - Slurm: `shard.sbatch`, a job array `--array=0-(K-1)` whose task `$SLURM_ARRAY_TASK_ID`
//!   runs `argus run … --shards K --shard $SLURM_ARRAY_TASK_ID` into `<shared>/shard-<i>`;
//!   `merge.sbatch`, `argus merge` of the shards into `<shared>/merged`; `submit.sh`, which
//!   submits the array and then the merge with `--dependency=afterok:<array job id>`.
//! - Kubernetes: `k8s/shards-job.yaml`, an Indexed Job (`completionMode: Indexed`,
//!   `completions: K`, the shard from `$JOB_COMPLETION_INDEX`), `k8s/merge-job.yaml`, and
//!   `k8s/submit.sh`, which waits for the first to complete before it applies the second;
//!   `k8s/shared-pvc.yaml`, the shared volume (ReadWriteMany) they mount at `/shared`.
//!
//! The shards write to a shared directory; nothing needs a database. Every shard's range
//! is [`crate::shard::shard_range`]: argus computes it from the task index, the scripts
//! only print it.

use std::fmt::Write as _;
use std::ops::Range;
use std::path::Path;

use argus_io::output::write_atomic;

use crate::error::CliError;
use crate::shard::shard_range;

/// What to plan.
#[derive(Debug, Clone)]
pub(crate) struct Plan<'a> {
    /// Scenario name.
    pub(crate) scenario: &'a str,
    /// The campaign's runs.
    pub(crate) runs: Range<u64>,
    /// Number of shards.
    pub(crate) shards: u64,
    /// Base seed.
    pub(crate) seed: u64,
    /// `--set key=value` settings, passed to every shard.
    pub(crate) settings: &'a [String],
    /// Shared directory (absolute) of the Slurm jobs.
    pub(crate) shared: &'a Path,
    /// The `argus` executable of the Slurm jobs.
    pub(crate) argus: &'a str,
    /// Container image of the Kubernetes jobs (with `argus` on its `PATH`).
    pub(crate) image: &'a str,
}

/// `s` quoted for a POSIX shell (single quotes; a `'` inside as `'\''`).
fn sh(s: &str) -> String {
    if !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_./=:,+@%".contains(c))
    {
        return s.to_owned();
    }
    format!("'{}'", s.replace('\'', r"'\''"))
}

/// `s` as a YAML double-quoted scalar (a JSON string is one).
fn yaml_str(s: &str) -> String {
    serde_json::to_string(s).unwrap_or_else(|_| "\"\"".to_owned())
}

impl Plan<'_> {
    /// The `argus run` arguments after the executable, up to `--out`, for shard index
    /// `index` (a shell word such as `"$SLURM_ARRAY_TASK_ID"`).
    fn run_args(&self, index: &str) -> String {
        let mut a = format!(
            "run {} --runs {}..{} --shards {} --shard {index} --seed {}",
            self.scenario, self.runs.start, self.runs.end, self.shards, self.seed
        );
        for s in self.settings {
            let _ = write!(a, " --set {}", sh(s));
        }
        a
    }

    fn job_name(&self) -> String {
        format!("argus-{}", self.scenario)
    }

    /// The shard range formula in shell arithmetic, for the scripts' log line.
    fn range_shell(&self, index: &str) -> String {
        let (a, n, k) = (
            self.runs.start,
            self.runs.end - self.runs.start,
            self.shards,
        );
        format!(
            "start=$(( {a} + {n} * {index} / {k} )); end=$(( {a} + {n} * ({index} + 1) / {k} ))"
        )
    }

    fn shard_sbatch(&self) -> String {
        let shared = self.shared.display().to_string();
        format!(
            r#"#!/bin/bash
# Shards of `argus run {sc} --runs {a}..{b}` (written by `argus campaign plan`): task i of
# the array computes shard i of {k} into {shared}/shard-i.
#SBATCH --job-name={name}
#SBATCH --array=0-{last}
#SBATCH --cpus-per-task=1
#SBATCH --output={shared_q}/logs/shard-%a.out
set -euo pipefail
i=${{SLURM_ARRAY_TASK_ID:?run this as a Slurm array task (sbatch), or set SLURM_ARRAY_TASK_ID}}
{range}
echo "argus shard $i of {k}: runs $start..$end on $(hostname)"
export RAYON_NUM_THREADS=${{SLURM_CPUS_PER_TASK:-1}}
exec {argus} {args} --out {shared_q}/shard-"$i"
"#,
            sc = self.scenario,
            a = self.runs.start,
            b = self.runs.end,
            k = self.shards,
            last = self.shards - 1,
            name = self.job_name(),
            shared_q = sh(&shared),
            range = self.range_shell("i"),
            argus = sh(self.argus),
            args = self.run_args("\"$i\""),
        )
    }

    fn merge_sbatch(&self) -> String {
        let shared = sh(&self.shared.display().to_string());
        format!(
            r#"#!/bin/bash
# Merge of the {k} shards (submitted by submit.sh with --dependency=afterok on the array):
# `argus merge` checks that every shard and run is there once before it reduces.
#SBATCH --job-name={name}-merge
#SBATCH --cpus-per-task=1
#SBATCH --output={shared}/logs/merge.out
set -euo pipefail
exec {argus} merge {sc} {shared}/shard-* --out {shared}/merged
"#,
            k = self.shards,
            name = self.job_name(),
            argus = sh(self.argus),
            sc = self.scenario,
        )
    }

    fn submit_sh(&self) -> String {
        let shared = sh(&self.shared.display().to_string());
        format!(
            r#"#!/bin/bash
# Submits the shards as a job array, then the merge once every task succeeded.
set -euo pipefail
cd "$(dirname "$0")"
mkdir -p {shared}/logs
array=$(sbatch --parsable shard.sbatch)
array=${{array%%;*}}
merge=$(sbatch --parsable --dependency=afterok:"$array" merge.sbatch)
merge=${{merge%%;*}}
echo "shards: job $array (array 0-{last}); merge: job $merge"
echo "merged report: {shared}/merged/summary.json"
echo "$array $merge" > .jobs
"#,
            last = self.shards - 1,
        )
    }

    /// The end of a Kubernetes Job's pod template: its container mounts the shared
    /// volume ([`Self::k8s_pvc`]'s claim) at `/shared`.
    fn shared_volume(&self) -> String {
        format!(
            r#"          volumeMounts:
            - name: shared
              mountPath: /shared
      volumes:
        - name: shared
          persistentVolumeClaim:
            claimName: {name}-shared
"#,
            name = self.job_name(),
        )
    }

    fn k8s_shards(&self) -> String {
        let cmd = format!(
            "exec argus {} --out /shared/shard-\"$JOB_COMPLETION_INDEX\"",
            self.run_args("\"$JOB_COMPLETION_INDEX\"")
        );
        format!(
            r#"# Shards of `argus run {sc} --runs {a}..{b}` as an Indexed Job: completion index i
# computes shard i of {k} into /shared/shard-i (written by `argus campaign plan`).
apiVersion: batch/v1
kind: Job
metadata:
  name: {name}-shards
spec:
  completionMode: Indexed
  completions: {k}
  parallelism: {k}
  backoffLimit: {backoff}
  template:
    spec:
      restartPolicy: Never
      containers:
        - name: shard
          image: {image}
          command: ["sh", "-c"]
          args:
            - {cmd}
          env:
            - name: RAYON_NUM_THREADS
              value: "1"
          resources:
            requests:
              cpu: "1"
{volume}"#,
            sc = self.scenario,
            a = self.runs.start,
            b = self.runs.end,
            k = self.shards,
            backoff = 3 * self.shards,
            name = self.job_name(),
            volume = self.shared_volume(),
            image = yaml_str(self.image),
            cmd = yaml_str(&cmd),
        )
    }

    fn k8s_merge(&self) -> String {
        let cmd = format!(
            "exec argus merge {} /shared/shard-* --out /shared/merged",
            self.scenario
        );
        format!(
            r#"# The merge of the {k} shards: apply it once {name}-shards has completed (k8s/submit.sh).
apiVersion: batch/v1
kind: Job
metadata:
  name: {name}-merge
spec:
  completions: 1
  backoffLimit: 2
  template:
    spec:
      restartPolicy: Never
      containers:
        - name: merge
          image: {image}
          command: ["sh", "-c"]
          args:
            - {cmd}
{volume}"#,
            k = self.shards,
            name = self.job_name(),
            image = yaml_str(self.image),
            cmd = yaml_str(&cmd),
            volume = self.shared_volume(),
        )
    }

    fn k8s_pvc(&self) -> String {
        format!(
            r#"# The directory the shards write and the merge reads: a volume every pod mounts at
# /shared (ReadWriteMany: NFS, CephFS, a cloud file store …).
apiVersion: v1
kind: PersistentVolumeClaim
metadata:
  name: {name}-shared
spec:
  accessModes: ["ReadWriteMany"]
  resources:
    requests:
      storage: 10Gi
"#,
            name = self.job_name(),
        )
    }

    fn k8s_submit(&self) -> String {
        format!(
            r#"#!/bin/bash
# Applies the shared volume and the Indexed Job, waits for every index to complete, then
# applies the merge Job and waits for it.
set -euo pipefail
cd "$(dirname "$0")"
kubectl apply -f shared-pvc.yaml
kubectl apply -f shards-job.yaml
kubectl wait --for=condition=complete --timeout=24h job/{name}-shards
kubectl apply -f merge-job.yaml
kubectl wait --for=condition=complete --timeout=1h job/{name}-merge
echo "merged report: /shared/merged/summary.json on the volume {name}-shared"
"#,
            name = self.job_name(),
        )
    }
}

/// Writes the plan's files into `out` and returns what to print: the files and how to
/// submit them.
///
/// # Errors
/// [`CliError::Usage`] for a shard count the runs cannot fill; [`CliError::Io`].
pub(crate) fn write(plan: &Plan<'_>, out: &Path) -> Result<Vec<String>, CliError> {
    // Every shard non-empty (the same check `argus run --shards` makes).
    for i in 0..plan.shards.max(1) {
        shard_range(&plan.runs, plan.shards, i)?;
    }
    let files: [(&str, String, bool); 8] = [
        ("shard.sbatch", plan.shard_sbatch(), true),
        ("merge.sbatch", plan.merge_sbatch(), true),
        ("submit.sh", plan.submit_sh(), true),
        ("k8s/shards-job.yaml", plan.k8s_shards(), false),
        ("k8s/merge-job.yaml", plan.k8s_merge(), false),
        ("k8s/shared-pvc.yaml", plan.k8s_pvc(), false),
        ("k8s/submit.sh", plan.k8s_submit(), true),
        ("README", readme(plan, out), false),
    ];
    let mut lines = Vec::new();
    for (name, text, exec) in files {
        let path = out.join(name);
        write_atomic(&path, text.as_bytes())?;
        if exec {
            set_executable(&path)?;
        }
        lines.push(format!("wrote {}", path.display()));
    }
    lines.extend(readme(plan, out).lines().map(str::to_owned));
    Ok(lines)
}

fn readme(plan: &Plan<'_>, out: &Path) -> String {
    let shared = plan.shared.display();
    let o = out.display();
    format!(
        "campaign: argus run {} --runs {}..{} --seed {} in {} shards\n\
         Slurm:      bash {o}/submit.sh   (array 0-{}, then the merge with --dependency=afterok; shards in {shared}/shard-<i>, report in {shared}/merged)\n\
         Kubernetes: bash {o}/k8s/submit.sh   (Indexed Job of {} completions on image {}, then the merge Job; volume {}-shared at /shared)\n\
         a failed shard i: re-submit index i (e.g. sbatch --array=i {o}/shard.sbatch), then merge again: its output is identical\n",
        plan.scenario,
        plan.runs.start,
        plan.runs.end,
        plan.seed,
        plan.shards,
        plan.shards - 1,
        plan.shards,
        plan.image,
        plan.job_name(),
    )
}

#[cfg(unix)]
fn set_executable(path: &Path) -> Result<(), CliError> {
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o755))
        .map_err(|e| CliError::io(path, e))
}

#[cfg(not(unix))]
fn set_executable(_path: &Path) -> Result<(), CliError> {
    Ok(())
}
