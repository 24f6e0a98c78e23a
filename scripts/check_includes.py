#!/usr/bin/env python3
"""Check every #include of emulator/ and models/ against scripts/include_rules.json.

Usage: scripts/check_includes.py [SOURCE_DIR]   (default: the repository this script is in)
Exit 0 and one summary line when every include is allowed; exit 1 listing each crossing
("file:line: includes X, which its rule (prefix P) does not allow") and each temporary
exception that no longer occurs. Standard library only.
"""
import json
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')
SOURCE_SUFFIXES = (".hpp", ".cpp", ".h", ".cc", ".in")


def rule_for(path, rules):
    """The rule whose 'files' is the longest prefix of `path`, or None."""
    best = None
    for rule in rules:
        if path.startswith(rule["files"]) and (best is None or len(rule["files"]) > len(best["files"])):
            best = rule
    return best


def allowed(target, prefixes):
    return any(target.startswith(p) for p in prefixes)


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    with open(os.path.join(root, "scripts", "include_rules.json"), encoding="utf-8") as f:
        table = json.load(f)
    third_party = table["third_party"]
    rules = table["rules"]
    errors = []
    used_temporary = set()
    files = includes = 0
    for top in ("emulator", "models"):
        for dirpath, _, names in os.walk(os.path.join(root, top)):
            for name in sorted(names):
                if not name.endswith(SOURCE_SUFFIXES):
                    continue
                full = os.path.join(dirpath, name)
                path = os.path.relpath(full, root).replace(os.sep, "/")
                rule = rule_for(path, rules)
                files += 1
                with open(full, encoding="utf-8", errors="replace") as f:
                    lines = f.readlines()
                for number, line in enumerate(lines, 1):
                    m = INCLUDE.match(line)
                    if not m:
                        continue
                    quote, target = m.groups()
                    project = quote == '"' and "/" in target
                    library = quote == "<" and allowed(target, third_party)
                    if not project and not library:
                        continue   # the C++ and POSIX headers, and same-folder quoted includes
                    includes += 1
                    if rule is None:
                        errors.append(f"{path}:{number}: no rule in scripts/include_rules.json governs this file")
                        continue
                    if allowed(target, rule["may_include"]):
                        continue
                    if target in rule.get("temporary", []):
                        used_temporary.add((rule["files"], target))
                        continue
                    errors.append(f"{path}:{number}: includes {target}, which its rule (files \"{rule['files']}\") does not allow")
    for rule in rules:
        for target in rule.get("temporary", []):
            if (rule["files"], target) not in used_temporary:
                errors.append(f"scripts/include_rules.json: the temporary exception {target} for \"{rule['files']}\" "
                              "is no longer used: remove it")
    if errors:
        print("\n".join(errors))
        print(f"{len(errors)} include rule violation(s) in {files} files")
        return 1
    temporary = sum(len(r.get("temporary", [])) for r in rules)
    print(f"include rules: {includes} project and library includes in {files} files follow the layer order "
          f"({temporary} temporary exception(s) left)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
