"""Every Catch2 test case is one ctest entry that selects it and nothing else.

catch_discover_tests makes one ctest entry per name Catch2 lists, passing the name back to the
program as its test spec. A name that ctest or Catch2 reads as something else splits into entries
that select nothing (a ';' is ctest's list separator) or is taken for an option (a leading '-'),
and such an entry would pass without running anything. Each entry's own command is run here with
--list-test-names-only: it must list exactly the test case the entry is named after, and together
the entries must list each of the program's test cases once.

Usage: catch_entries.py CTEST BUILD_DIR TEST_PROGRAM..."""
import concurrent.futures
import json
import os
import subprocess
import sys


def listed(command, cwd=None):
    result = subprocess.run([*command, "--list-test-names-only"], cwd=cwd, capture_output=True, text=True)
    return result.stdout.splitlines()


def entry_selects(entry):
    cwd = next((p["value"] for p in entry.get("properties", []) if p["name"] == "WORKING_DIRECTORY"), None)
    return listed(entry["command"], cwd)


ctest, build_dir, *programs = sys.argv[1:]
shown = subprocess.run([ctest, "--test-dir", build_dir, "--show-only=json-v1"], capture_output=True, text=True, check=True)
tests = json.loads(shown.stdout)["tests"]
problems = []
for program in programs:
    cases = listed([program])
    entries = [t for t in tests if "command" in t and os.path.realpath(t["command"][0]) == os.path.realpath(program)]
    selected = []
    # Most of the time goes into starting the programs: a few at once.
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        selections = pool.map(entry_selects, entries)
    for entry, names in zip(entries, selections):
        if len(names) != 1 or not entry["name"].endswith(names[0]):
            what = names if len(names) <= 3 else f"{len(names)} test cases"
            problems.append(f"ctest entry {entry['name']!r} selects {what} of {program}")
        selected += names
    if len(entries) != len(cases):
        problems.append(f"{program}: {len(entries)} ctest entries for {len(cases)} test cases")
    for case in sorted(set(cases) - set(selected)):
        problems.append(f"{program}: no ctest entry runs {case!r}")
    print(f"{program}: {len(cases)} test cases, {len(entries)} ctest entries")

for p in problems:
    print("FAIL:", p)
sys.exit(1 if problems else 0)
