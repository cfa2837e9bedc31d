#!/usr/bin/env python3
"""Snakemake's --cluster-status for SLURM: prints running, success or failed for the job id it is given.

Asks scontrol (the controller knows a job until MinJobAge after it ended), then sacct (when accounting is on).
A job neither knows any more is reported as success: Snakemake then checks that the job's files are there and
fails the job when they are not, so no failure passes unseen.
"""
import subprocess
import sys

RUNNING = {"PENDING", "CONFIGURING", "RUNNING", "COMPLETING", "SUSPENDED", "REQUEUED", "RESIZING", "SIGNALING",
           "STAGE_OUT", "REQUEUE_HOLD", "REQUEUE_FED", "RESV_DEL_HOLD", "STOPPED"}


def state_from_scontrol(job):
    done = subprocess.run(["scontrol", "-o", "show", "job", job], capture_output=True, text=True)
    for field in done.stdout.split() if done.returncode == 0 else []:
        if field.startswith("JobState="):
            return field.split("=", 1)[1]
    return None


def state_from_sacct(job):
    done = subprocess.run(["sacct", "-X", "-n", "-P", "-o", "State", "-j", job], capture_output=True, text=True)
    lines = [line.strip() for line in done.stdout.splitlines() if line.strip()] if done.returncode == 0 else []
    return lines[0].split()[0] if lines else None  # "CANCELLED by 0" -> CANCELLED


def main():
    job = sys.argv[1].split(";")[0]  # sbatch --parsable prints "id" or "id;cluster"
    state = state_from_scontrol(job) or state_from_sacct(job)
    if state is None:
        print("success")
    elif state in RUNNING:
        print("running")
    else:
        print("success" if state == "COMPLETED" else "failed")


if __name__ == "__main__":
    main()
