#!/usr/bin/env python3
"""k8s_check.py: offline check of a Cavalry Indexed Job manifest.

Usage: k8s_check.py JOB.yaml [--print-args]

Without a cluster, kubectl cannot validate (even --dry-run=client asks an API
server for its schema), so this walks the manifest against the Job API's types
as the official Python client generates them from Kubernetes' OpenAPI spec:
every field must exist in its object's type, hold a value of that type, and
required fields must be set. Then it checks the rules the API server applies
to Jobs and the contract with cavalry-batch. It cannot check what only a
cluster knows: admission rules, quotas, the image, the claim, the GPU plugin.
With --print-args it prints the container's arguments, one a line.
Exit status: 0 valid, 1 invalid (one line per problem on stderr), 2 usage.
"""
import json
import re
import sys

import yaml
from kubernetes import client

PRIMITIVES = {"str": str, "int": int, "bool": bool, "float": (int, float)}
DNS_LABEL = re.compile(r"^[a-z0-9]([-a-z0-9]*[a-z0-9])?$")


def walk(value, type_name, path, problems):
    """Checks VALUE against the client's TYPE_NAME; PATH names it in messages."""
    if value is None:  # null leaves a field unset; build() finds missing ones
        return
    m = re.match(r"^list\[(.*)\]$", type_name)
    if m:
        if not isinstance(value, list):
            problems.append(f"{path}: wants a list")
            return
        for i, v in enumerate(value):
            walk(v, m.group(1), f"{path}[{i}]", problems)
        return
    m = re.match(r"^dict\(str, (.*)\)$", type_name)
    if m:
        if not isinstance(value, dict):
            problems.append(f"{path}: wants a map")
            return
        for k, v in value.items():
            # Quantities (resource limits) are int-or-string in the API.
            inner = m.group(1)
            if path.endswith((".limits", ".requests")) and isinstance(v, (int, float)):
                continue
            walk(v, inner, f"{path}.{k}", problems)
        return
    if type_name in PRIMITIVES:
        ok = isinstance(value, PRIMITIVES[type_name]) and not (
            type_name != "bool" and isinstance(value, bool))
        if not ok:
            problems.append(f"{path}: wants {type_name}, not {value!r}")
        return
    if type_name in ("object", "datetime", "date"):
        return
    model = getattr(client, type_name)
    if not isinstance(value, dict):
        problems.append(f"{path}: wants a {type_name} map")
        return
    by_json = {j: p for p, j in model.attribute_map.items()}
    for key, v in value.items():
        if key not in by_json:
            problems.append(f"{path}.{key}: no such field in {type_name}")
            continue
        walk(v, model.openapi_types[by_json[key]], f"{path}.{key}", problems)


def build(doc, problems):
    """Builds the client's V1Job, whose setters reject missing required fields."""
    class Response:  # what ApiClient.deserialize reads: the body, as JSON
        data = json.dumps(doc)
    try:
        return client.ApiClient().deserialize(Response, "V1Job")
    except (ValueError, TypeError) as e:
        problems.append(f"V1Job: {e}")
        return None


def job_rules(job, problems):
    """What the API server checks for an Indexed Job, and Cavalry's contract."""
    spec = job.spec
    if job.api_version != "batch/v1" or job.kind != "Job":
        problems.append("not a batch/v1 Job")
    if not job.metadata or not job.metadata.name or not DNS_LABEL.match(job.metadata.name):
        problems.append("metadata.name: wants a DNS label")
    if spec.completion_mode != "Indexed":
        problems.append("spec.completionMode: wants Indexed (pods get JOB_COMPLETION_INDEX)")
    if not spec.completions or spec.completions < 1:
        problems.append("spec.completions: wants the shard count, at least 1")
    if spec.parallelism is not None and spec.parallelism < 0:
        problems.append("spec.parallelism: must not be negative")
    pod = spec.template.spec
    if pod is None:
        problems.append("spec.template.spec: missing")
        return []
    if pod.restart_policy not in ("Never", "OnFailure"):
        problems.append("spec.template.spec.restartPolicy: a Job wants Never or OnFailure")
    volumes = {v.name for v in pod.volumes or []}
    if len(pod.containers) != 1:
        problems.append("spec.template.spec.containers: wants one container")
    c = pod.containers[0]
    where = f"container {c.name}"
    if not DNS_LABEL.match(c.name):
        problems.append(f"{where}: name wants a DNS label")
    if not c.image:
        problems.append(f"{where}: no image")
    limits = (c.resources.limits or {}) if c.resources else {}
    if str(limits.get("nvidia.com/gpu")) != "1":
        problems.append(f"{where}: wants resources.limits nvidia.com/gpu: 1")
    mounts = {}
    for m in c.volume_mounts or []:
        if m.name not in volumes:
            problems.append(f"{where}: volumeMount {m.name} names no volume")
        if not m.mount_path.startswith("/"):
            problems.append(f"{where}: mountPath {m.mount_path} is not absolute")
        mounts[m.mount_path.rstrip("/") + "/"] = m
    env = {e.name: e.value for e in c.env or []}
    if "JOB_COMPLETION_INDEX" in env:
        problems.append(f"{where}: sets JOB_COMPLETION_INDEX, which Kubernetes gives each pod")
    if "graphics" not in (env.get("NVIDIA_DRIVER_CAPABILITIES") or "").split(","):
        problems.append(f"{where}: NVIDIA_DRIVER_CAPABILITIES wants graphics (EGL)")
    command = (c.command or []) + (c.args or [])
    if not command or not command[0].endswith("cavalry-batch"):
        problems.append(f"{where}: does not run cavalry-batch")
        return []
    args = command[1:]
    counts = [a.split("=", 1)[1] for a in args if a.startswith("--shard-count=")]
    if counts != [str(spec.completions)]:
        problems.append(f"{where}: wants --shard-count={spec.completions}, as spec.completions")
    if any(a.startswith("--shard-index") for a in args):
        problems.append(f"{where}: --shard-index would override JOB_COMPLETION_INDEX")
    manifest = args[-1] if args else ""
    if not any(manifest.startswith(p) for p in mounts):
        problems.append(f"{where}: manifest {manifest!r} is not on a mounted volume")
    if c.working_dir and not any((c.working_dir.rstrip("/") + "/").startswith(p) for p in mounts):
        problems.append(f"{where}: workingDir {c.working_dir} is not on a mounted volume")
    return args


def main(argv):
    if len(argv) not in (2, 3) or (len(argv) == 3 and argv[2] != "--print-args"):
        print("usage: k8s_check.py JOB.yaml [--print-args]", file=sys.stderr)
        return 2
    with open(argv[1]) as f:
        docs = [d for d in yaml.safe_load_all(f) if d is not None]
    problems = []
    if len(docs) != 1:
        problems.append(f"wants one document, not {len(docs)}")
    else:
        walk(docs[0], "V1Job", "Job", problems)
        job = None if problems else build(docs[0], problems)
        args = job_rules(job, problems) if job else []
    for p in problems:
        print(f"{argv[1]}: {p}", file=sys.stderr)
    if problems:
        return 1
    if len(argv) == 3:
        for a in args:
            print(a)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
