"""The options' declarations against what users read: `ramap mapper -h` and the options README
names, with their defaults."""

import re

import ramap
from conftest import SOURCE_DIR, run_cli


# docs/options.md against `ramap options`, the ranges stated once, every option in a table and
# every option a message names declared: scripts/check_options.py (ctest option_declarations).


def test_mapper_help_shows_every_declaration_with_its_default():
    help_text = run_cli("mapper", "-h").stdout
    for name, default in ramap.mapper_option_defaults().items():
        # A renamed option lists its former names after its name: "--New,--Old TYPE=default".
        shown = re.search(rf"^\s*--{re.escape(name)}(?:,--[\w.]+)* (\S+)(?:\s|$)", help_text,
                          re.MULTILINE)
        assert shown, name
        type_and_default = shown.group(1)
        if default:
            assert type_and_default.endswith("=" + default), (name, type_and_default)


def every_commands_options():
    """{"--Section.option": default} over every command's -h."""
    commands = [line.split()[0] for line in run_cli("help").stdout.splitlines()
                if line.startswith("  ") and not line.strip().startswith("ramap")]
    assert "mapper" in commands and "synthesize" in commands
    known = {}
    for command in commands:
        for match in re.finditer(r"^\s*(--[\w.]+(?:,--[\w.]+)*) (\S+)(?:\s|$)",
                                 run_cli(command, "-h").stdout, re.MULTILINE):
            for name in match.group(1).split(","):
                known[name] = match.group(2).partition("=")[2]
    return known


def test_readme_names_only_options_that_exist_with_their_defaults():
    readme = (SOURCE_DIR / "README.md").read_text()
    known = every_commands_options()
    rows = [line for line in readme.splitlines() if line.startswith("| `--")]
    assert rows, "README's options table"
    for row in rows:
        for name in re.findall(r"`(--[A-Z]\w*\.\w+)[\s`]", row):
            assert name in known, f"README names {name}, which no command defines"
        for name, default in re.findall(r"`(--[A-Z]\w*\.\w+)[^`]*` \(default ([^)\s:,;]+)", row):
            assert known[name] == default, f"README: {name} default {default}, declared {known[name]}"
