#!/usr/bin/env python3
"""README.md's Commands block against the programs' own --help.

The ```sh block after "## Commands" holds a usage line (with its indented continuation lines)
per subcommand of binpick and one for binpickd. Checked: the subcommands are those binpick --help
lists (a group such as calibrate by its own subcommands, "calibrate rig"); every --option a line
names is one the subcommand's --help shows; every option its --help shows is named, or belongs to
an option group ("Board options:") that the line names as "[board options]".

usage: readme_commands_test.py README.md BINPICK BINPICKD
"""
import re
import subprocess
import sys

OPTION = re.compile(r"--[a-z][a-z0-9-]*")
GROUP = re.compile(r"\[([a-z][a-z -]* options)\]", re.IGNORECASE)
failures = []


def fail(message):
    failures.append(message)
    print("FAIL: " + message)


def commands_block(readme_path):
    text = open(readme_path, encoding="utf-8").read()
    section = text.split("\n## Commands\n", 1)
    if len(section) != 2:
        sys.exit("README.md has no '## Commands' section")
    match = re.search(r"```sh\n(.*?)```", section[1], re.DOTALL)
    if not match:
        sys.exit("README.md's Commands section has no ```sh block")
    return match.group(1)


def readme_usages(block):
    """{"detect": text, "calibrate rig": text, ...} for binpick, and binpickd's text."""
    usages, current = {}, None
    for line in block.splitlines():
        words = line.split()
        if not words:
            continue
        if line[0].isspace():
            if current is None:
                fail("README: a continuation line before any command: " + line)
                continue
            usages[current] += " " + line
            continue
        if words[0] == "binpickd":
            current = "binpickd"
        elif words[0] == "binpick" and len(words) > 1 and not words[1].startswith("-"):
            current = words[1]
            if current == "calibrate" and len(words) > 2:
                current += " " + words[2]
        else:
            fail("README: a line that is no command: " + line)
            continue
        usages[current] = usages.get(current, "") + " " + line
    return usages


def help_text(program, words):
    result = subprocess.run([program] + words + ["--help"], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"{' '.join([program] + words)} --help exited {result.returncode}: {result.stderr}")
    return result.stdout


def parse_help(text):
    """The subcommands and {option: section heading} of a --help text."""
    subcommands, options, section = [], {}, ""
    for line in text.splitlines():
        if line and not line[0].isspace() and line.endswith(":"):
            section = line[:-1]
            continue
        words = line.split()
        if not line.startswith("  ") or not words:
            continue
        if section == "Subcommands":
            subcommands.append(words[0])
        elif words[0].startswith("-"):
            for name in OPTION.findall(words[0]):
                if name not in ("--help", "--version"):
                    options[name] = section
    return subcommands, options


def program_commands(binpick):
    """Every runnable subcommand path of binpick: a group by its own subcommands."""
    commands = []
    pending = [[name] for name in parse_help(help_text(binpick, []))[0]]
    while pending:
        words = pending.pop(0)
        children = parse_help(help_text(binpick, words))[0]
        if children:
            pending += [words + [child] for child in children]
        else:
            commands.append(" ".join(words))
    return commands


def check(name, usage, help_output):
    _, options = parse_help(help_output)
    named = set(OPTION.findall(usage))
    groups = {group.lower() for group in GROUP.findall(usage)}
    headings = {section.lower() for section in options.values()}
    for option in sorted(named - set(options)):
        fail(f"README names {option} for '{name}', which its --help does not show")
    for group in sorted(groups - headings):
        fail(f"README names [{group}] for '{name}', which its --help has no group of")
    for option, section in sorted(options.items()):
        if option not in named and section.lower() not in groups:
            fail(f"'{name}' takes {option} ({section}), which README does not name")


def main():
    readme, binpick, binpickd = sys.argv[1:4]
    usages = readme_usages(commands_block(readme))
    commands = program_commands(binpick)
    readme_commands = {name for name in usages if name != "binpickd"}
    for name in sorted(set(commands) - readme_commands):
        fail(f"README lists no 'binpick {name}'")
    for name in sorted(readme_commands - set(commands)):
        fail(f"README lists 'binpick {name}', which binpick --help does not")
    for name in sorted(readme_commands & set(commands)):
        check("binpick " + name, usages[name], help_text(binpick, name.split()))
    if "binpickd" not in usages:
        fail("README lists no binpickd line")
    else:
        check("binpickd", usages["binpickd"], help_text(binpickd, []))
    if failures:
        sys.exit(f"{len(failures)} differences between README.md's Commands and --help")
    print(f"README.md's Commands match --help: {len(commands)} subcommands and binpickd")


if __name__ == "__main__":
    main()
