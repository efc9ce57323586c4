"""Replays the special-file and size cases (bounded_inputs_cases.py) against
bowg_convert_vocabulary, bowg_evaluate and the live nodelet
(loop_detector_node: its start-up, and its ~load_database service), and
prints a table: case | program | outcome | seconds | peak MB over baseline.

Run by scripts/check_bounded_inputs.sh (which puts the workspace's ROS
environment in place): python3 check_bounded_inputs.py WORKSPACE REPO.

Each program's baseline is the same program refusing a missing file (for
the image case: the evaluator on a folder of one small image; for
~load_database: the node answering for a missing file, and the memory it had
before the call): its seconds and peak resident memory are the cost of
starting it, which the limits below do not count. A case fails when it is accepted, hangs (no
answer within the timeout), crashes, is refused without naming the file,
takes more than 1 s over the baseline or peaks more than 100 MB over it."""

import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time

from bounded_inputs_cases import make_cases

TIMEOUT_S = 10.0
MAX_SECONDS_OVER = 1.0
MAX_MB_OVER = 100.0
# A run past this resident size is stopped ("hog"): it has failed already, and
# a loader reading /dev/zero would otherwise take the machine's memory.
HOG_KB = 1 << 20
BAD = ("accepted", "hung", "crashed", "unnamed", "hog")


def vm_hwm_kb(pid):
    """Peak resident memory of a live process so far (kB), or 0."""
    try:
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


class Run:
    """One program run: outcome, seconds to its answer, peak RSS (kB), output."""

    def __init__(self, outcome, seconds, peak_kb, output):
        self.outcome, self.seconds, self.peak_kb, self.output = outcome, seconds, peak_kb, output


def run(cmd, env, stop_on=None, timeout=TIMEOUT_S):
    """Runs `cmd`; stops it when a line matches `stop_on` (outcome
    "started"), kills it after `timeout` ("hung"). Otherwise the outcome is
    its exit: "exit 0", "exit N" or "crashed" (a signal, a sanitizer abort);
    "hog" when it grows past HOG_KB."""
    start = time.monotonic()
    # In the scratch folder: the evaluator writes its outputs there.
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env,
                            start_new_session=True, cwd=env["BOWG_SCRATCH"])
    lines, started = [], threading.Event()

    def read():
        for raw in proc.stdout:
            line = raw.decode("utf-8", "replace")
            lines.append(line)
            if stop_on and re.search(stop_on, line):
                started.set()

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    peak = 0
    while True:
        pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
        seconds = time.monotonic() - start
        if pid:
            proc.returncode = status
            reader.join(2)
            if os.WIFSIGNALED(status):
                outcome = "crashed"
            else:
                code = os.WEXITSTATUS(status)
                outcome = "crashed" if code >= 128 else "exit %d" % code
            return Run(outcome, seconds, max(peak, usage.ru_maxrss), "".join(lines))
        peak = max(peak, vm_hwm_kb(proc.pid))
        if started.is_set() or seconds > timeout or peak > HOG_KB:
            stop(proc)
            outcome = "started" if started.is_set() else "hog" if peak > HOG_KB else "hung"
            return Run(outcome, seconds, peak, "".join(lines))
        time.sleep(0.01)


def stop(proc):
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except OSError:
        pass
    proc.wait()


def judge(r, path, accept_marker=None):
    """refused / skipped / accepted / hung / crashed / unnamed."""
    if r.outcome in ("hung", "crashed", "hog"):
        return r.outcome
    named = path in r.output
    if r.outcome == "exit 0" or r.outcome == "started":
        if accept_marker and named and re.search(accept_marker, r.output):
            return "refused" if r.outcome == "started" else "skipped"
        return "accepted"
    return "refused" if named else "unnamed"


class Table:
    def __init__(self):
        self.rows, self.failures = [], 0

    def add(self, case, program, verdict, r, base):
        over_s = r.seconds - base.seconds
        over_mb = (r.peak_kb - base.peak_kb) / 1024.0
        bad = verdict in BAD or over_s > MAX_SECONDS_OVER or over_mb > MAX_MB_OVER
        self.failures += bad
        self.rows.append((case, program, verdict, r.seconds, over_mb, "FAIL" if bad else "ok"))
        print("  %-28s %-24s %-9s %7.2f s %8.1f MB  %s" % self.rows[-1], flush=True)
        if bad and verdict != "hung":
            for line in r.output.strip().splitlines()[-3:]:
                print("      | " + line[:200])

    def baseline(self, program, r, case="missing file"):
        """The cost of starting `program` (peak: its whole peak memory)."""
        print("  %-28s %-24s %-9s %7.2f s %8.1f MB  (baseline)"
              % (case, program, r.outcome, r.seconds, r.peak_kb / 1024.0), flush=True)


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def start_master(env):
    port = free_port()
    env["ROS_MASTER_URI"] = "http://127.0.0.1:%d" % port
    os.environ["ROS_MASTER_URI"] = env["ROS_MASTER_URI"]  # for rospy, in this process
    master = subprocess.Popen(["roscore", "-p", str(port)], stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, env=env, start_new_session=True)
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        try:
            socket.create_connection(("127.0.0.1", port), 0.2).close()
            time.sleep(1.0)  # rosout and the parameter server follow the port
            return master
        except OSError:
            time.sleep(0.2)
    stop(master)
    raise SystemExit("check_bounded_inputs: roscore did not start")


def stop_master(master):
    """SIGINT: roscore shuts its rosmaster and rosout down (a kill would
    leave them running)."""
    master.send_signal(signal.SIGINT)
    try:
        master.wait(15)
    except subprocess.TimeoutExpired:
        stop(master)


def unblock_fifo(path):
    """Ends a FIFO a loader is stuck on (no effect when nobody reads it)."""
    try:
        fd = os.open(path, os.O_WRONLY | os.O_NONBLOCK)
        os.close(fd)
    except OSError:
        pass


def tools_cases(table, bins, env, vocabulary, small_images, huge_images, tmp, vocabularies):
    converted = os.path.join(tmp, "converted.bowgvoc")
    convert = lambda p: [bins["bowg_convert_vocabulary"], p, converted]
    evaluate_voc = lambda p: [bins["bowg_evaluate"], "--images", small_images, "--vocabulary", p,
                              "--quiet"]
    missing = os.path.join(tmp, "missing.bowgvoc")
    for program, cmd in (("bowg_convert_vocabulary", convert), ("bowg_evaluate", evaluate_voc)):
        base = run(cmd(missing), env)
        table.baseline(program, base)
        for case, path in vocabularies:
            r = run(cmd(path), env)
            table.add(case, program, judge(r, path), r, base)
            if case.startswith("fifo"):
                unblock_fifo(path)
    # An image too large to decode: refused, or skipped with its name logged.
    base = run(evaluate_voc(vocabulary), env)
    table.baseline("bowg_evaluate", base, "one 64x64 image")
    for case, folder in huge_images:
        image = os.path.join(folder, sorted(os.listdir(folder))[0])
        r = run([bins["bowg_evaluate"], "--images", folder, "--vocabulary", vocabulary, "--quiet"],
                env)
        table.add(case, "bowg_evaluate", judge(r, image, accept_marker=re.escape(image)), r, base)


_node_runs = [0]


def node_cmd(bins, params):
    """A node of a name of its own: private parameters of earlier runs stay
    on the parameter server and must not reach it. Returns (cmd, name)."""
    _node_runs[0] += 1
    name = "bowg_replay_%d" % _node_runs[0]
    # Line-buffered: the node's "ready" line must arrive while it runs.
    cmd = ["stdbuf", "-oL", "-eL", bins["loop_detector_node"], "__name:=" + name]
    return cmd + ["_%s:=%s" % kv for kv in params.items()], "/" + name


def node_startup_cases(table, bins, env, vocabulary, tmp, vocabularies, databases):
    ready = r"bowg_ros ready"
    missing = os.path.join(tmp, "missing.bowgvoc")
    base = run(node_cmd(bins, {"vocabulary_path": missing})[0], env, stop_on=ready)
    table.baseline("node vocabulary:=", base)
    for case, path in vocabularies:
        r = run(node_cmd(bins, {"vocabulary_path": path})[0], env, stop_on=ready)
        table.add(case, "node vocabulary:=", judge(r, path), r, base)
        unblock_fifo(path)
    # A database that cannot be loaded at start-up: an error naming it, and
    # the node starts with an empty database.
    missing_db = os.path.join(tmp, "missing.bowgdb")
    params = {"vocabulary_path": vocabulary}
    base = run(node_cmd(bins, dict(params, database_load_path=missing_db))[0], env,
               stop_on=ready)
    table.baseline("node database_load_path", base)
    for case, path in databases:
        r = run(node_cmd(bins, dict(params, database_load_path=path))[0], env, stop_on=ready)
        table.add(case, "node database_load_path", judge(r, path, "could not load"), r, base)
        unblock_fifo(path)


def call_load(node, path, pid):
    """~load_database of `node` (process `pid`) on a thread of its own:
    (outcome so far: None = answered, "hung" or "hog"; the answer; seconds)."""
    import rospy
    from bowg_ros.srv import LoadDatabase
    box = {}

    def call():
        try:
            box["response"] = rospy.ServiceProxy(node + "/load_database", LoadDatabase)(path)
        except Exception as e:  # noqa: BLE001 - a dead node is an outcome
            box["error"] = str(e)

    t = threading.Thread(target=call, daemon=True)
    start = time.monotonic()
    t.start()
    while t.is_alive():
        seconds = time.monotonic() - start
        if vm_hwm_kb(pid) > HOG_KB:
            return "hog", box, seconds
        if seconds > TIMEOUT_S:
            return "hung", box, seconds
        t.join(0.01)
    return None, box, time.monotonic() - start


def node_service_cases(table, bins, env, vocabulary, tmp, databases):
    started = []  # every node started, stopped whatever happens
    try:
        _service_cases(table, bins, env, vocabulary, tmp, databases, started)
    finally:
        for proc in started:
            if proc.poll() is None:
                stop(proc)


def _service_cases(table, bins, env, vocabulary, tmp, databases, started):
    import rospy
    proc = None
    missing = os.path.join(tmp, "missing.bowgdb")
    for case, path in [("missing file", missing)] + databases:
        if proc is None or proc.poll() is not None:
            cmd, node = node_cmd(bins, {"vocabulary_path": vocabulary})
            proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                    env=env, start_new_session=True)
            started.append(proc)
            rospy.wait_for_service(node + "/load_database", 30)
        before = vm_hwm_kb(proc.pid)
        stuck, box, seconds = call_load(node, path, proc.pid)
        peak = vm_hwm_kb(proc.pid) or before
        if stuck:
            outcome = stuck
        elif "error" in box:
            outcome = "crashed" if proc.poll() is not None else "exit 1"
        else:
            outcome = "exit 0" if box["response"].success else "exit 1"
        message = box["response"].message if "response" in box else box.get("error", "")
        r = Run(outcome, seconds, peak, message)
        if case == "missing file":
            base_seconds = seconds
            table.baseline("node ~load_database", Run(outcome, seconds, peak - before, message),
                           "missing file (growth)")
            continue
        # Memory over what the running node had before the call.
        table.add(case, "node ~load_database", judge(r, path), r,
                  Run("", base_seconds, before, ""))
        if stuck:
            unblock_fifo(path)
            stop(proc)
            proc = None


def main():
    ws, repo = sys.argv[1], sys.argv[2]
    lib = os.path.join(ws, "devel", "lib", "bowg_ros")
    bins = {n: os.path.join(lib, n)
            for n in ("bowg_convert_vocabulary", "bowg_evaluate", "loop_detector_node")}
    for name, path in bins.items():
        if not os.access(path, os.X_OK):
            raise SystemExit("check_bounded_inputs: %s is not built (%s): build it first"
                             % (name, path))
    vocabulary = os.path.join(repo, "data", "default_vocabulary.bowgvoc")
    tmp = tempfile.mkdtemp(prefix="bowg_bounded_inputs.")
    env = dict(os.environ, ROS_LOG_DIR=os.path.join(tmp, "ros_log"), BOWG_SCRATCH=tmp)
    master = None
    try:
        print("-- cases in %s" % tmp, flush=True)
        vocabularies, databases, huge_images, small_images = make_cases(tmp)
        table = Table()
        print("  %-28s %-24s %-9s %9s %11s" % ("case", "program", "outcome", "seconds",
                                                "peak over"), flush=True)
        tools_cases(table, bins, env, vocabulary, small_images, huge_images, tmp, vocabularies)
        master = start_master(env)
        node_startup_cases(table, bins, env, vocabulary, tmp, vocabularies, databases)
        node_service_cases(table, bins, env, vocabulary, tmp, databases)
        print("%d cases, %d failed (limits: refused or skipped with the file named, within "
              "%.0f s and %.0f MB over the program's baseline)"
              % (len(table.rows), table.failures, MAX_SECONDS_OVER, MAX_MB_OVER))
        return 1 if table.failures else 0
    finally:
        if master is not None:
            stop_master(master)
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
