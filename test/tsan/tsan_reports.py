#!/usr/bin/env python3
"""Sorts ThreadSanitizer report files (TSAN_OPTIONS log_path=...) of the
nodelet manager into the project's and ROS's own, for
scripts/check_thread_sanitizer.sh.

ROS's libraries (roscpp, nodelet, log4cxx, boost) are not instrumented: their
atomics are invisible to ThreadSanitizer, so it reports their reference
counting and the order in which they take their own mutexes, also where the
project's code is further down the stack (a message released in a callback,
a publisher's mutex taken while publishing). Those are ROS's. A report is the
project's when

  - a data race has, in one of its two access stacks, code of the project at
    the racing access, unless one of the two accesses is a deallocation run
    by a reference count (boost::detail::sp_counted*) with no hand-written
    code of the project between the count and the access;
  - a lock-order cycle has a mutex taken by the project's code (the first
    frame above the mutex wrappers is hand-written code of the project);
  - any other kind of report has a frame of the project's code.

Code of the project: the repository's files (hand-written), the message
headers generated in the workspace, and functions of the bowg and bowg_ros
namespaces by name (not a ROS template whose arguments name one of the
project's types); frames in the project's libraries that the runtime could
not name are named with addr2line first.

  tsan_reports.py REPO LIBDIR OURS_OUT ROS_OUT REPORT_FILE...

Writes the project's reports in full (frames named) to OURS_OUT, one line per
kind and place of ROS's to ROS_OUT, and prints "<project's> <ROS's>".
"""
import os
import re
import subprocess
import sys

FRAME = re.compile(r"^(\s*#\d+ )(.*)$")
UNNAMED = re.compile(r"<null> <null> \((libbowg[^+)]*)\+(0x[0-9a-f]+)\)")
KIND = re.compile(r"WARNING: ThreadSanitizer: ([a-z -]+)")
ACCESS = re.compile(r"^\s+(Previous )?(atomic )?(read|write|Read|Write) of size")
LOCK = re.compile(r"^\s+Mutex \S+ (acquired here|previously acquired)")
MUTEX_WRAPPERS = ("bits/std_mutex.h", "bits/unique_lock.h", "/mutex:", "/mutex ",
                  "boost/thread/", "gthr-default.h", "gthr-posix.h")


def name_frames(text, libdir):
    """Replaces frames of the project's libraries that the runtime left
    unnamed by addr2line's inline chains ("f file:line <- inlined in ...")."""
    wanted = {}
    for lib, addr in UNNAMED.findall(text):
        wanted.setdefault(lib, set()).add(addr)
    names = {}
    for lib, addrs in wanted.items():
        path = os.path.join(libdir, lib)
        if not os.path.exists(path):
            continue
        addrs = sorted(addrs)
        out = subprocess.run(["addr2line", "-a", "-C", "-f", "-i", "-e", path] + addrs,
                             capture_output=True, text=True, check=False).stdout.splitlines()
        current, chain = None, []
        for line in out + ["0x"]:
            if line.startswith("0x"):
                if current is not None:
                    pairs = [chain[i] + " " + chain[i + 1] for i in range(0, len(chain) - 1, 2)]
                    names[(lib, "0x%x" % int(current, 16))] = " <- inlined in ".join(pairs)
                current, chain = line if line != "0x" else None, []
            else:
                chain.append(line)
    return UNNAMED.sub(lambda m: "%s (%s+%s)" % (
        names.get((m.group(1), m.group(2)), "<null> <null>"), m.group(1), m.group(2)), text)


def stacks(report):
    """(heading, [frame text]) for every stack of the report."""
    result, heading, frames = [], None, []
    for line in report.splitlines():
        m = FRAME.match(line)
        if m:
            frames.append(m.group(2))
            continue
        if heading is not None and frames:
            result.append((heading, frames))
        heading, frames = line, []
    if heading is not None and frames:
        result.append((heading, frames))
    return result


def inline_parts(frame):
    return frame.split(" <- inlined in ")


class Project:
    def __init__(self, repo):
        self.repo = repo.rstrip("/") + "/"

    def hand_written(self, part):
        return "/src/bowg_ros/" in part or (self.repo in part and "/.ws/" not in part
                                            and "/devel/" not in part)

    def any_code(self, part):
        # By name only where the function itself is the project's: a ROS
        # template instantiated for one of the project's messages
        # (ros::serialization::serializeServiceResponse<bowg_ros::...>) is
        # ROS's code.
        return (self.hand_written(part) or "/devel/include/bowg_ros/" in part
                or re.search(r"\bbowg(_ros)?::", without_arguments(part)) is not None)


def without_arguments(part):
    """A frame's text without its template argument and parameter lists."""
    out, depth = [], 0
    for ch in part:
        if ch in "<(":
            depth += 1
        elif ch in ">)" and depth > 0:
            depth -= 1
        elif depth == 0:
            out.append(ch)
    return "".join(out)


def outside_runtime(frames):
    """The inline parts of a stack, innermost first, without the runtime's."""
    parts = []
    for f in frames:
        if "libsanitizer" in f or "libtsan" in f:
            continue
        parts.extend(inline_parts(f))
    return parts


def refcount_deallocation(parts, project):
    """A deallocation run by a reference count, with no hand-written code of
    the project between the count and the access."""
    for p in parts:
        if "boost::detail::sp_counted" in p or "boost::checked_array_delete" in p:
            return True
        if project.hand_written(p):
            return False
    return False


def is_projects(report, project):
    kind = KIND.search(report).group(1).strip()
    all_stacks = stacks(report)
    if kind == "data race":
        accesses = [outside_runtime(f) for h, f in all_stacks if ACCESS.match(h)]
        if any(refcount_deallocation(p, project) for p in accesses):
            return False
        return any(p and project.any_code(p[0]) for p in accesses)
    if kind.startswith("lock-order-inversion"):
        for heading, frames in all_stacks:
            if not LOCK.match(heading):
                continue
            parts = [p for p in outside_runtime(frames)
                     if not any(w in p for w in MUTEX_WRAPPERS)]
            if parts and project.hand_written(parts[0]):
                return True
        return False
    return any(project.any_code(p) for _, f in all_stacks for x in f for p in inline_parts(x))


def main(argv):
    repo, libdir, ours_path, ros_path, files = argv[1], argv[2], argv[3], argv[4], argv[5:]
    project = Project(repo)
    ours, ros = [], {}
    for path in files:
        with open(path, errors="replace") as f:
            text = name_frames(f.read(), libdir)
        for report in text.split("==================\n"):
            kind = KIND.search(report)
            if not kind:
                continue
            if is_projects(report, project):
                ours.append(report)
                continue
            frames = [x for _, f in stacks(report) for x in f]
            place = next((inline_parts(f)[0].split(" (")[0] for f in frames
                          if "libsanitizer" not in f), "?")
            key = (kind.group(1).strip(), place[:160])
            ros[key] = ros.get(key, 0) + 1
    with open(ours_path, "w") as out:
        out.write("==================\n".join(ours))
    with open(ros_path, "w") as out:
        for (kind, place), n in sorted(ros.items(), key=lambda kv: -kv[1]):
            out.write("%5d  %s  in %s\n" % (n, kind, place))
    print(len(ours), sum(ros.values()))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
