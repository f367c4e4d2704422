"""The options' declarations against what users read: `ramap mapper -h`, docs/options.md and the
options README names."""

import re

import ramap
from conftest import SOURCE_DIR, run_cli


def test_docs_options_is_the_declarations():
    generated = run_cli("options").stdout
    assert (SOURCE_DIR / "docs" / "options.md").read_text() == generated, \
        "docs/options.md is stale: run `ramap options > docs/options.md`"
    for name, default in ramap.mapper_option_defaults().items():
        assert f"| `--{name}` | {default} |" in generated, name


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


def test_every_option_an_error_names_exists():
    """Messages name options as "--Section.option" (a literal, or a prefix variable and a key):
    each must be an option some command defines."""
    known = every_commands_options()
    named = {}
    for path in sorted((SOURCE_DIR / "src").rglob("*.cc")):
        text = path.read_text()
        names = re.findall(r'"(--[A-Z]\w*\.\w*[a-z0-9])"', text)
        for variable, prefix in re.findall(r'(\w+) = "(--[A-Z]\w*\.\w*)"', text):
            names += [prefix + key for key in re.findall(rf'\b{variable} \+ "(\w+)"', text)]
        for name in names:
            named.setdefault(name, path.relative_to(SOURCE_DIR))
    assert len(named) > 100
    unknown = {name: str(path) for name, path in named.items() if name not in known}
    assert not unknown, f"messages name options no command defines: {unknown}"


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
