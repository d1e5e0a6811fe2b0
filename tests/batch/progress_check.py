#!/usr/bin/python3
"""progress_check.py: checks a cavalry-batch machine progress stream for the
shell tests, with a real parser.

  progress_check.py json FILE [EXPECT...]    --progress=json lines
  progress_check.py openjd FILE              --progress=openjd lines
  progress_check.py dryrun FILE [EXPECT...]  --dry-run --json document

EXPECT items are checks by name (see the functions below), e.g.
"done=3", "not_started=b,c", "errors", "stdin", "fields" (every event's
fields, as cavalry-batch(1) lists them; "fields_gpu": and a job's events
name their GPU). Prints what is wrong and
exits 1; exits 0 when every check holds."""
import datetime
import json
import os
import re
import sys

ISO = re.compile(r"^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z$")
# The order of a batch's phases, then of each job's (progress.h enum cv_phase).
BATCH_PHASES = ["manifest_read", "scene_load", "gpu_open"]
JOB_PHASES = ["bvh_build", "program_compile", "render", "colour", "write"]

problems = []

# The fields cavalry-batch(1), PROGRESS EVENTS, lists for each event, with
# their types: "int" (not a boolean), "num" (int or float), "str",
# "strs" (a list of strings).
FIELDS = {
    "batch_started": {"manifest": "str", "jobs": "strs"},
    "phase": {"phase": "str"},
    "job_started": {"index": "int", "total": "int", "target_spp": "int"},
    "progress": {"spp": "int", "target_spp": "int", "percent": "num", "eta_s": "num",
                 "rays_per_s": "num", "elapsed_s": "num"},
    "job_finished": {"spp": "int", "seconds": "num", "scene_seconds": "num",
                     "render_seconds": "num", "outputs": "strs"},
    "error": {"message": "str"},
    "batch_finished": {"done": "int", "partial": "int", "failed": "int", "skipped": "int",
                       "not_started": "strs"},
}
for _end in ("job_partial", "job_failed", "job_skipped"):
    FIELDS[_end] = FIELDS["job_finished"]
JOB_EVENTS = ("job_started", "progress", "job_finished", "job_partial", "job_failed",
              "job_skipped")


def fail(msg):
    problems.append(msg)


def parse_time(s):
    if not isinstance(s, str) or not ISO.match(s):
        fail("time %r is not ISO 8601 UTC with milliseconds" % (s,))
        return None
    return datetime.datetime.strptime(s, "%Y-%m-%dT%H:%M:%S.%fZ")


def of_type(v, kind):
    if kind == "int":
        return isinstance(v, int) and not isinstance(v, bool)
    if kind == "num":
        return isinstance(v, (int, float)) and not isinstance(v, bool)
    if kind == "str":
        return isinstance(v, str)
    return isinstance(v, list) and all(isinstance(x, str) for x in v)


def check_fields(events, job_gpu):
    """Every event is one the page names, with each of its fields present
    and of its type; job events name their job (and GPU where asked)."""
    for e in events:
        name = e.get("event")
        if name not in FIELDS:
            fail("an event the page does not name: %r" % (e,))
            continue
        for key, kind in FIELDS[name].items():
            if key not in e:
                fail("%s without %s: %r" % (name, key, e))
            elif not of_type(e[key], kind):
                fail("%s: %s is not %s: %r" % (name, key, kind, e))
        if name in JOB_EVENTS and not of_type(e.get("job"), "str"):
            fail("%s without its job: %r" % (name, e))
        if "gpu" in e and not (of_type(e["gpu"], "int") and e["gpu"] >= 0):
            fail("gpu is not a device index: %r" % (e,))
        if job_gpu and "job" in e and "gpu" not in e:
            fail("a job's event without its gpu: %r" % (e,))
        if name == "phase" and e.get("phase") not in BATCH_PHASES + JOB_PHASES:
            fail("unknown phase: %r" % (e,))
        if "file" in e and not of_type(e["file"], "str"):
            fail("file is not a string: %r" % (e,))
        if name == "job_started" and not 1 <= e.get("index", 0) <= e.get("total", 0):
            fail("index not within 1..total: %r" % (e,))
        if name == "progress" and not (0 <= e.get("percent", -1) <= 100 and
                                       e.get("eta_s", -1) >= 0 and e.get("rays_per_s", -1) >= 0
                                       and e.get("elapsed_s", -1) >= 0):
            fail("progress out of range: %r" % (e,))
        if name == "job_failed" and not of_type(e.get("error"), "str"):
            fail("job_failed without its error: %r" % (e,))
        if name == "job_skipped" and not of_type(e.get("detail"), "str"):
            fail("job_skipped without why (detail): %r" % (e,))
        if "detail" in e and not of_type(e["detail"], "str"):
            fail("detail is not a string: %r" % (e,))
        if name == "error" and ("file" in e or "line" in e or "column" in e):
            if not (of_type(e.get("file"), "str") and of_type(e.get("line"), "int") and
                    of_type(e.get("column"), "int") and e["line"] >= 1 and e["column"] >= 1):
                fail("error with part of a place (file, line, column from 1): %r" % (e,))


def check_json(path, expect):
    events = []
    with open(path) as f:
        for n, line in enumerate(f, 1):
            try:
                events.append(json.loads(line))
            except ValueError as e:
                fail("line %d is not JSON (%s): %r" % (n, e, line))
    if not events:
        fail("no events")
        return
    last = None
    for e in events:
        t = parse_time(e.get("time"))
        if t is not None and last is not None and t < last:
            fail("time goes back at %r" % (e,))
        last = t or last
    names = [e["event"] for e in events]
    if names[-1] != "batch_finished":
        fail("the last event is %s, not batch_finished" % names[-1])
    finished = events[-1]
    if not isinstance(finished.get("not_started"), list):
        fail("batch_finished has no not_started list")
    # Batch phases in order, before any job's.
    seen = [e["phase"] for e in events if e["event"] == "phase" and "job" not in e]
    order = [p for p in BATCH_PHASES if p in seen]
    if "errors" not in expect:
        if seen[:1] != ["manifest_read"] or order != sorted(order, key=BATCH_PHASES.index) or \
                [p for p in seen if p not in BATCH_PHASES]:
            fail("batch phases out of order: %r" % seen)
        for p in BATCH_PHASES:
            if p not in seen:
                fail("no %s phase" % p)
    # Per job: phases in order (colour comes right before the PNG's write,
    # which may follow an EXR's write), progress within [0, 100].
    jobs = {}
    for e in events:
        if "job" in e:
            jobs.setdefault(e["job"], []).append(e)
    for job, evs in jobs.items():
        phases = [e["phase"] for e in evs if e["event"] == "phase"]
        ranks = [JOB_PHASES.index(p) for p in phases]
        first_write = phases.index("write") if "write" in phases else len(phases)
        head = ranks[:first_write]
        if head != sorted(head):
            fail("job %s: phases out of order: %r" % (job, phases))
        if "colour" in phases and phases[phases.index("colour") + 1:][:1] != ["write"]:
            fail("job %s: colour not followed by a write: %r" % (job, phases))
        end = [e for e in evs if e["event"].startswith("job_") and e["event"] != "job_started"]
        if end and end[-1]["event"] == "job_finished":
            for p in ("program_compile", "render", "write"):
                if p not in phases:
                    fail("job %s: no %s phase" % (job, p))
            if phases.count("write") != len(end[-1]["outputs"]):
                fail("job %s: %d writes for outputs %r" % (job, phases.count("write"),
                                                            end[-1]["outputs"]))
        for e in evs:
            if e["event"] == "progress":
                if not 0 <= e["percent"] <= 100 or "eta_s" not in e or e["eta_s"] < 0:
                    fail("job %s: bad progress event %r" % (job, e))
            if e["event"] in ("job_finished", "job_partial", "job_failed"):
                if not isinstance(e.get("outputs"), list):
                    fail("job %s: outputs is not a list: %r" % (job, e))
                for o in e.get("outputs", []):
                    if not os.path.isfile(o):
                        fail("job %s: output %s does not exist" % (job, o))
                if not e["seconds"] >= e["render_seconds"] >= 0 or e["scene_seconds"] < 0:
                    fail("job %s: seconds do not add up: %r" % (job, e))
                if e["seconds"] < e["scene_seconds"]:
                    fail("job %s: seconds leave out the scene's: %r" % (job, e))
        pct = [e["percent"] for e in evs if e["event"] == "progress"]
        if pct != sorted(pct):
            fail("job %s: percent goes back: %r" % (job, pct))
    for x in expect:
        if x.startswith("done="):
            if finished.get("done") != int(x[5:]):
                fail("batch_finished: done %r, expected %s" % (finished.get("done"), x[5:]))
        elif x.startswith("not_started="):
            want = [s for s in x[12:].split(",") if s]
            if finished.get("not_started") != want:
                fail("not_started %r, expected %r" % (finished.get("not_started"), want))
        elif x == "errors" or x.startswith("file="):
            errs = [e for e in events if e["event"] == "error"]
            if not errs:
                fail("no error events")
            for e in errs:
                if not isinstance(e.get("line"), int) or not isinstance(e.get("column"), int) \
                        or not e.get("file") or not e.get("message"):
                    fail("error event without file, line, column, message: %r" % (e,))
                if x.startswith("file=") and e.get("file") != x[5:]:
                    fail("error in %r, expected %s" % (e.get("file"), x[5:]))
        elif x.startswith("scene_seconds_once"):
            paid = [e for e in events if e["event"] == "job_finished" and e["scene_seconds"] > 0]
            if len(paid) != 1:
                fail("the scene's time is reported %d times, expected once" % len(paid))
        elif x.startswith("workers="):
            # a multi-GPU batch: events from each worker named, and every
            # event about a job says its worker and device
            want = sorted(int(w) for w in x[8:].split(","))
            seen = sorted({e["worker"] for e in events if "worker" in e})
            if seen != want:
                fail("events from workers %r, expected %r" % (seen, want))
            for e in events:
                if "job" in e and not (isinstance(e.get("worker"), int) and
                                       isinstance(e.get("gpu"), int)):
                    fail("job event without worker and gpu: %r" % (e,))
        elif x == "fields" or x == "fields_gpu":
            check_fields(events, x == "fields_gpu")
        elif x == "no_workers":
            if [e for e in events if "worker" in e]:
                fail("events name workers in a single process")
        elif x == "each_once":
            # every selected job starts once and ends once, but those
            # batch_finished says never started
            started = [e for e in events if e["event"] == "batch_started"]
            if len(started) != 1:
                fail("%d batch_started events" % len(started))
            never = finished.get("not_started") or []
            for job in started[0]["jobs"] if started else []:
                evs = jobs.get(job, [])
                n_start = len([e for e in evs if e["event"] == "job_started"])
                n_end = len([e for e in evs if e["event"] in
                             ("job_finished", "job_partial", "job_failed", "job_skipped")])
                if (n_start > 1 or n_end != 1) and not (job in never and n_start + n_end == 0):
                    fail("job %s: started %d times, ended %d times" % (job, n_start, n_end))
        else:
            fail("unknown expectation %r" % x)


def check_openjd(path):
    last = -1
    lines = open(path).read().splitlines()
    if not lines:
        fail("no lines")
    for line in lines:
        m = re.match(r"^openjd_(progress|status|fail): (.*)$", line)
        if not m:
            fail("not an OpenJD line: %r" % line)
            continue
        if m.group(1) == "progress":
            v = float(m.group(2))
            if not 0 <= v <= 100 or v < last:
                fail("progress %r after %r" % (v, last))
            last = v
    if last != 100:
        fail("progress ends at %r, not 100" % last)


def check_dryrun(path, expect):
    doc = json.load(open(path))
    jobs = {j["name"]: j for j in doc["jobs"]}
    for j in doc["jobs"]:
        for key, kind in (("name", str), ("scene", str), ("outputs", list), ("resolution", list),
                          ("spp", int), ("integrator", str), ("seed", int), ("shard", int)):
            if not isinstance(j.get(key), kind):
                fail("job %r: %s is not a %s" % (j.get("name"), key, kind.__name__))
    for x in expect:
        # name.key=value, value compared as JSON ("a.spp=3", "a.resolution=[8,6]")
        m = re.match(r"^([^.=]+)\.([a-z_]+)=(.*)$", x)
        if m:
            got = jobs.get(m.group(1), {}).get(m.group(2), "<missing>")
            if got != json.loads(m.group(3)):
                fail("%s.%s is %r, expected %s" % (m.group(1), m.group(2), got, m.group(3)))
        elif x.startswith("jobs="):
            want = [s for s in x[5:].split(",") if s]
            if [j["name"] for j in doc["jobs"]] != want:
                fail("jobs %r, expected %r" % ([j["name"] for j in doc["jobs"]], want))
        else:
            fail("unknown expectation %r" % x)


def main():
    kind, path, expect = sys.argv[1], sys.argv[2], sys.argv[3:]
    try:
        {"json": lambda: check_json(path, expect), "openjd": lambda: check_openjd(path),
         "dryrun": lambda: check_dryrun(path, expect)}[kind]()
    except (ValueError, KeyError, OSError) as e:
        fail("%s: %r" % (type(e).__name__, e))
    for p in problems:
        print("# %s: %s" % (path, p))
    sys.exit(1 if problems else 0)


main()
