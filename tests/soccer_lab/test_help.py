"""The help of every command: each option explained with its default, each paper with its own
options, the preset choices read from the registries, no wording only the developers would
understand."""

from __future__ import annotations

import argparse
import re

import pytest

from soccer_env import presets
from soccer_env.perception.options import BALL_FILTERS
from soccer_lab.cli import COMMANDS, main, paper_parser, parsers
from soccer_lab.papers import PAPERS

#: Options that have no default to state: what they name is only there when given.
NO_DEFAULT = {("train", "--resume"), ("train", "--opponent"), ("bench", "--profile")}


def _options(parser: argparse.ArgumentParser) -> list[argparse.Action]:
    return [a for a in parser._actions
            if a.option_strings and not isinstance(a, argparse._HelpAction)]


def _rendered_help(parser: argparse.ArgumentParser, action: argparse.Action) -> str:
    """The option's help as ``--help`` prints it (default appended), on one line."""
    text = parser._get_formatter()._expand_help(action)
    return " ".join(text.split())


@pytest.fixture(scope="module")
def all_parsers() -> dict[str, argparse.ArgumentParser]:
    return parsers()


def test_every_command_but_play_has_a_parser(all_parsers):
    assert set(COMMANDS) - {"play"} <= set(all_parsers)
    assert {f"paper {name}" for name in PAPERS} <= set(all_parsers)


def test_every_option_has_help_that_states_its_default(all_parsers):
    checked = 0
    for command, parser in all_parsers.items():
        for action in _options(parser):
            option = next(o for o in action.option_strings if o.startswith("--"))
            where = f"soccer-env {command} {option}"
            assert action.help and action.help.strip(), f"{where} has no help"
            text = _rendered_help(parser, action)
            flag = action.nargs == 0
            default = action.default
            if flag:
                assert "(default: " not in text, where
            elif default not in (None, []):
                assert text.count("(default: ") == 1, f"{where}: {text}"
                assert f"(default: {default})" in text, f"{where}: {text}"
            elif default is None and (command.split()[0], option) not in NO_DEFAULT:
                assert text.count("(default: ") == 1, (
                    f"{where} defaults to None: its help must say what happens without it, "
                    f"as '(default: ...)': {text}")
            checked += 1
    assert checked > 80


def test_train_states_the_configuration_defaults(all_parsers):
    import dataclasses

    from agents.runs.training import TrainConfig
    from soccer_lab.commands.train_options import FIELD_OPTIONS

    defaults = {f.name: f.default for f in dataclasses.fields(TrainConfig)}
    p = all_parsers["train"]
    by_dest = {a.dest: a for a in _options(p)}
    for field, dest in FIELD_OPTIONS:
        if field in ("batched",):
            continue
        shown = str(defaults[field])
        if field == "algorithm":
            shown = shown.lower()
        assert f"(default: {shown}" in _rendered_help(p, by_dest[dest]), field


def test_paper_help_has_that_papers_options_only(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["paper", "ekf", "--help"])
    assert exc.value.code == 0
    text = capsys.readouterr().out
    assert "--shots" in text and "--no-closed-loop" in text and "Zhao et al. (2012)" in text
    for other in ("--runs", "--particles", "--trials", "--matches", "--walks"):
        assert other not in text
    with pytest.raises(SystemExit) as exc:
        main(["paper", "ekf", "--runs", "3"])
    assert exc.value.code == 2
    assert "unrecognized arguments: --runs 3" in capsys.readouterr().err


def test_paper_help_lists_every_paper_on_one_line_by_authors_and_year(capsys):
    with pytest.raises(SystemExit):
        main(["paper", "--help"])
    lines = capsys.readouterr().out.splitlines()
    for name in PAPERS:
        line = next(x for x in lines if x.split()[:1] == [name])
        assert PAPERS.description(name) in line and len(line) <= 80, line
        assert re.search(r"^  \w+ +[A-Z][a-z]+ (et al\.|and [A-Z][a-z]+) \(\d{4}\): ", line)


@pytest.mark.parametrize("argv", [
    ["paper", "ekf", "--episodes", "20", "--no-closed-loop"],
    ["paper", "team", "--matches", "8", "--duration", "60", "--no-closed-loop"],
    ["paper", "team", "--no-keeper"],
    ["paper", "ungm", "--runs", "10000", "--out", "paper_output"],
    ["paper", "localization", "--walks", "2", "--workers", "1"],
    ["paper", "hough", "--trials", "1"],
    ["paper", "meanshift", "--out", "paper_output"],
    ["paper", "following", "--episodes", "2"],
])
def test_documented_paper_command_lines_still_parse(argv):
    paper, _ = paper_parser()
    args = paper.parse_args(argv[1:])
    assert args.name == argv[1]


def test_perception_offers_every_robot_kinds_presets_grouped(all_parsers):
    for command in ("train", "eval"):
        p = all_parsers[command]
        text = _rendered_help(p, next(a for a in _options(p) if a.dest == "perception"))
        ssl = f"SSL robots (overhead vision): {', '.join(presets.VISION)}"
        humanoid = f"humanoids (head camera): {', '.join(presets.HEAD_CAMERAS)}"
        assert ssl in text and humanoid in text, text
        robot = next(a for a in _options(p) if a.dest == "robot")
        assert list(robot.choices) == list(presets.ROBOTS)
        ball_filter = next(a for a in _options(p) if a.dest == "ball_filter")
        assert list(ball_filter.choices) == list(BALL_FILTERS)


def test_perception_takes_a_humanoid_camera_for_a_humanoid_robot():
    from soccer_lab.cli_args import env_kwargs_from_args
    from soccer_lab.commands import evaluate

    p = evaluate.parser()
    args = p.parse_args(["--robot", "humanoid-2012", "--perception", "kidsize-2012"])
    assert env_kwargs_from_args(args) == {"robot": "humanoid-2012",
                                          "perception": "kidsize-2012"}
    args = p.parse_args(["--env-kwarg", "robot=humanoid", "--perception", "kidsize",
                         "--ball-filter", "kf"])
    assert env_kwargs_from_args(args) == {"robot": "humanoid", "perception": {
        "camera": "kidsize", "ball_filter": "kf"}}
    args = p.parse_args(["--perception", "kidsize-2012"])  # the default robot: SSL
    with pytest.raises(ValueError, match="not a sensor preset of robot 'ssl'; SSL robots "
                                         r"\(overhead vision\) take ideal, ssl-2012"):
        env_kwargs_from_args(args)


def test_an_unknown_or_mismatched_preset_is_refused_naming_the_choices(capsys, tmp_path):
    with pytest.raises(SystemExit) as exc:
        main(["eval", "--perception", "foggy", "--out", str(tmp_path)])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "unknown sensor preset 'foggy'; choose from SSL robots (overhead vision): ideal, " \
           "ssl-2012, realistic, harsh; humanoids (head camera): ideal, kidsize-2012, " \
           "kidsize" in err
    with pytest.raises(SystemExit):
        main(["eval", "--robot", "humanoid-2012", "--perception", "harsh", "--out",
              str(tmp_path)])
    assert "--perception harsh: not a sensor preset of robot 'humanoid-2012'; humanoids " \
           "(head camera) take ideal, kidsize-2012, kidsize" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        main(["train", "--eval-perception", "kidsize", "--out", str(tmp_path / "run")])
    assert "--eval-perception kidsize: not a sensor preset of robot 'ssl'" in \
        capsys.readouterr().err
    with pytest.raises(SystemExit):
        main(["train", "--robot", "nao", "--out", str(tmp_path / "run")])
    assert "invalid choice: 'nao' (choose from 'ssl', 'ssl-2012', 'humanoid', " \
           "'humanoid-2012')" in capsys.readouterr().err
    assert not (tmp_path / "run").exists()


def test_help_has_no_wording_for_developers_only(all_parsers, capsys):
    main(["--help"])
    texts = [capsys.readouterr().out] + [p.format_help() for p in all_parsers.values()]
    for text in texts:
        assert not re.search(r"\b(aims?|issues?|TODO|stage \d)\b|paper 00\d", text,
                             re.IGNORECASE), text
