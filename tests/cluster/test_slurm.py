"""`rse-gen batch --shard auto` on a real Slurm (Debian's slurmctld, slurmd
and munge, make test-cluster installs them) that this test starts on this
machine and stops again: one controller, one compute node, its own munge
key, ports, state and log folders. It submits scripts/slurm/rse-batch.sbatch
(the script docs/guide.md shows) as an array job: the array's tree equals
one uninterrupted run's, byte for byte, also when one task is requeued
mid-way; a dependent job checks the whole tree."""

from __future__ import annotations

import os
import shutil
import signal
import socket
import subprocess
import time
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
RSE_GEN = REPO / "target" / "release" / "rse-gen"
SCRIPT = REPO / "scripts" / "slurm" / "rse-batch.sbatch"
DAEMONS = ("munged", "slurmctld", "slurmd")
TARGETS = "obj,mujoco"


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def config(home: Path, host: str) -> str:
    ctld, slurmd = free_port(), free_port()
    return f"""ClusterName=rsetest
SlurmctldHost={host}
SlurmctldPort={ctld}
SlurmdPort={slurmd}
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket={home}/munge.sock
StateSaveLocation={home}/state
SlurmdSpoolDir={home}/spool
SlurmctldPidFile={home}/slurmctld.pid
SlurmdPidFile={home}/slurmd.pid
SlurmctldLogFile={home}/slurmctld.log
SlurmdLogFile={home}/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
PlugStackConfig=/dev/null
NodeName={host} CPUs=2 State=UNKNOWN
PartitionName=rse Nodes={host} Default=YES MaxTime=INFINITE State=UP
"""


def run(*args: str, env: dict, check: bool = True) -> str:
    done = subprocess.run(args, env=env, capture_output=True, text=True, timeout=120)
    if check and done.returncode != 0:
        raise AssertionError(f"{' '.join(args)}: exit {done.returncode}: {done.stderr}")
    return done.stdout


@pytest.fixture(scope="module")
def slurm(tmp_path_factory):
    """A one-node Slurm with its own munge; stopped, and checked gone, after."""
    missing = [d for d in DAEMONS if shutil.which(d) is None]
    if missing:
        pytest.fail(f"{', '.join(missing)}: not installed; scripts/test-cluster.sh installs slurmctld, slurmd and munge")
    if not RSE_GEN.is_file():
        pytest.fail(f"{RSE_GEN}: build it first (cargo build --release -p rse-cli; scripts/test-cluster.sh does)")
    home = tmp_path_factory.mktemp("slurm")
    (home / "state").mkdir()
    (home / "spool").mkdir()
    key = home / "munge.key"
    key.write_bytes(os.urandom(1024))
    key.chmod(0o400)
    host = socket.gethostname()
    (home / "slurm.conf").write_text(config(home, host))
    env = {**os.environ, "SLURM_CONF": str(home / "slurm.conf"), "PATH": f"{RSE_GEN.parent}:{os.environ['PATH']}"}
    for name in list(env):
        if name.startswith("SLURM_") and name != "SLURM_CONF":
            del env[name]
    logs = {d: open(home / f"{d}.out", "w") for d in DAEMONS}
    commands = {
        "munged": ["munged", "-F", "-f", f"--socket={home}/munge.sock", f"--key-file={key}",
                   f"--log-file={home}/munged.log", f"--pid-file={home}/munged.pid", f"--seed-file={home}/munged.seed"],
        "slurmctld": ["slurmctld", "-D", "-f", str(home / "slurm.conf")],
        "slurmd": ["slurmd", "-D", "-f", str(home / "slurm.conf"), "-N", host],
    }  # fmt: skip
    daemons: dict[str, subprocess.Popen] = {}
    try:
        for name in DAEMONS:
            daemons[name] = subprocess.Popen(commands[name], env=env, stdout=logs[name], stderr=subprocess.STDOUT)
            time.sleep(1.0)
            if daemons[name].poll() is not None:
                raise AssertionError(f"{name} did not start: {(home / f'{name}.out').read_text()[-2000:]}")
        deadline = time.monotonic() + 60
        while "idle" not in run("sinfo", "-h", "-o", "%t", env=env, check=False):
            if time.monotonic() > deadline:
                raise AssertionError(f"the node never became idle: {run('sinfo', env=env, check=False)}")
            time.sleep(0.5)
        yield env, home
    finally:
        for name in reversed(DAEMONS):
            if name in daemons and daemons[name].poll() is None:
                daemons[name].send_signal(signal.SIGTERM)
        for process in daemons.values():
            try:
                process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
        for log in logs.values():
            log.close()
    # Ours are gone, and so are the job steps slurmd started (slurmstepd
    # names no folder: on a machine running a Slurm of its own, this check
    # would see that one's too).
    deadline = time.monotonic() + 20
    while left := [
        name
        for name, pattern in [*((d, f"{d}.*{home}") for d in DAEMONS), ("slurmstepd", "^slurmstepd")]
        if subprocess.run(["pgrep", "-f", pattern], capture_output=True).returncode == 0
    ]:
        assert time.monotonic() < deadline, f"still running: {left}"
        time.sleep(0.5)


def tree(root: Path) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


def wait_for(job: str, env: dict, timeout: float = 600) -> None:
    deadline = time.monotonic() + timeout
    while run("squeue", "-h", "-j", job, env=env, check=False).strip():
        assert time.monotonic() < deadline, run("squeue", env=env, check=False)
        time.sleep(0.5)


def job_field(job: str, field: str, env: dict) -> list[str]:
    """`field=` of every record `scontrol show job` prints for `job`."""
    text = run("scontrol", "-o", "show", "job", job, env=env)
    return [part.split("=", 1)[1] for line in text.splitlines() for part in line.split() if part.startswith(f"{field}=")]


def test_the_guides_array_script_writes_one_runs_tree_also_when_a_task_is_requeued(slurm, tmp_path) -> None:
    env, home = slurm
    scheme, amount = str(REPO / "schemes" / "nist_hill.csv"), 1200
    alone, spread = tmp_path / "alone", tmp_path / "spread"
    subprocess.run([str(RSE_GEN), "batch", scheme, "-o", str(alone), "--amount", str(amount), "--target", TARGETS],
                   check=True, capture_output=True)  # fmt: skip
    job = run("sbatch", "--parsable", "--array=0-3", "--cpus-per-task=1", f"--output={home}/task_%a.out",
              str(SCRIPT), scheme, str(spread), str(amount), TARGETS, env=env).strip()  # fmt: skip
    # Requeue task 0 once it has written some of its worlds (its shard is
    # 0, 4, 8, ...): Slurm kills it and runs it again from the start.
    deadline = time.monotonic() + 300
    while True:
        placed = [p for p in spread.glob("world_*") if int(p.name.split("_")[1]) % 4 == 0] if spread.exists() else []
        state = job_field(f"{job}_0", "JobState", env)
        if state == ["RUNNING"] and len(placed) >= 20:
            run("scontrol", "requeue", f"{job}_0", env=env)
            break
        assert state[:1] in (["PENDING"], ["RUNNING"]), f"task 0 ended before it could be requeued ({state}, {len(placed)} worlds): make the batch bigger"
        assert time.monotonic() < deadline
        time.sleep(0.05)
    wait_for(job, env)
    assert job_field(f"{job}_0", "Restarts", env) == ["1"], "task 0 ran again"
    assert set(job_field(job, "ExitCode", env)) == {"0:0"}, [(home / f"task_{k}.out").read_text() for k in range(4)]
    assert tree(spread) == tree(alone), "the array wrote one run's tree, byte for byte"

    check = run("sbatch", "--parsable", f"--dependency=afterok:{job}", f"--output={home}/check.out",
                "--wrap", f"rse-gen check {spread}", env=env).strip()  # fmt: skip
    wait_for(check, env)
    assert job_field(check, "ExitCode", env) == ["0:0"], (home / "check.out").read_text()
    assert f"checked {amount} worlds: {amount} good, 0 failed" in (home / "check.out").read_text()


def test_shard_auto_outside_an_array_job_is_a_usage_error(slurm, tmp_path) -> None:
    env, home = slurm
    job = run("sbatch", "--parsable", f"--output={home}/plain.out", "--wrap",
              f"rse-gen batch {REPO / 'schemes' / 'nist_hill.csv'} -o {tmp_path / 'w'} --amount 4 --shard auto", env=env).strip()  # fmt: skip
    wait_for(job, env)
    assert job_field(job, "ExitCode", env) == ["2:0"]
    assert "SLURM_ARRAY_TASK_ID is not set" in (home / "plain.out").read_text()
    assert not (tmp_path / "w").exists()
