"""Progress on a terminal: `btflut eval` under a pseudo-terminal draws its progress bar with
the time left (moving while a model trains), `btflut bake --predictor neural3` its training's,
and auto on a set of views its validation's and the chosen model's; piped, they print none.
Usage: terminal_check.py BTFLUT MATERIAL"""
import os
import pty
import subprocess
import sys
import tempfile


def under_terminal(argv):
    """Runs argv with stdout and stderr on a pseudo-terminal; returns what it wrote and its status."""
    main, side = pty.openpty()
    # The bar from the first step on, however fast the machine.
    env = dict(os.environ, BTFLUT_PROGRESS_AFTER="0")
    process = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=side, stderr=side, env=env)
    os.close(side)
    chunks = []
    while True:
        try:
            chunk = os.read(main, 4096)
        except OSError:  # the side closed: the process has ended
            break
        if not chunk:
            break
        chunks.append(chunk)
    os.close(main)
    return b"".join(chunks).decode(errors="replace"), process.wait()


def main():
    btflut, material = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as folder:
        # A fixed predictor: the bar is the subject, not auto's validation (which trains per fold).
        argv = [btflut, "eval", material, "--holdout", "every:3", "--modes", "lut,ptm", "--predictor", "hsh2",
                "--no-gl", "-o", os.path.join(folder, "eval")]
        text, status = under_terminal(argv)
        assert status == 0, text
        frames = [line for line in text.split("\r") if line.startswith("evaluating [")]
        assert frames, "no progress bar on a terminal:\n" + text[-2000:]
        assert any("s left" in f for f in frames), "no estimate of the time left:\n" + "\n".join(frames[-5:])
        steps = frames[-1].split("]")[1].split(",")[0].strip()
        done, total = (int(x) for x in steps.split("/"))
        assert done == total, frames[-1]
        piped = subprocess.run(argv[:-1] + [os.path.join(folder, "piped")], capture_output=True, text=True)
        assert piped.returncode == 0 and "evaluating [" not in piped.stderr, piped.stderr
        # A model fitted alone (a learned one, trained a few seconds): the bar moves within its
        # step (steps count in thousandths), not only when the training ends.
        argv = [btflut, "eval", material, "--holdout", "every:3", "--modes", "neural3", "--budget", "3s", "--no-gl",
                "-o", os.path.join(folder, "fit")]
        text, status = under_terminal(argv)
        assert status == 0, text
        fitting = [line for line in text.split("\r") if line.startswith("evaluating [")]
        within = [f for f in fitting if int(f.split("]")[1].split("/")[0]) % 1000 != 0]
        assert within, "the bar does not move while the model trains:\n" + "\n".join(fitting[-5:])
        # Training a learned model: its own bar, with the time left, to the end (a short time
        # budget: the same steps on any machine, a few seconds here).
        argv = [btflut, "bake", material, "--predictor", "neural3", "--budget", "2s", "-o",
                os.path.join(folder, "n.btflut")]
        text, status = under_terminal(argv)
        assert status == 0, text
        training = [line for line in text.split("\r") if line.startswith("training neural3 [")]
        assert training and any("s left" in f for f in training), "no training progress:\n" + text[-2000:]
        assert "1000/1000" in training[-1], training[-1]
        piped = subprocess.run(argv, capture_output=True, text=True)
        assert piped.returncode == 0 and "training" not in piped.stderr, piped.stderr
        # auto on a set of views: validation's bar moves while the learned candidate's folds
        # train, and the chosen model's training has its bar.
        views = os.path.join(folder, "views")
        subprocess.run([btflut, "synth", "--preset", "concrete", "--geometry", "btf-5", "--size", "64",
                        "--correlation-length", "4", "--samples", "1", "-q", "-o", views], check=True)
        text, status = under_terminal([btflut, "bake", views, "-o", os.path.join(folder, "views.btflut")])
        assert status == 0, text
        validating = [line for line in text.split("\r") if line.startswith("validating [")]
        assert any(int(f.split("]")[1].split("/")[0]) % 1000 != 0 for f in validating), \
            "validation's bar does not move while the folds train:\n" + "\n".join(validating[-5:])
        chosen = [line for line in text.split("\r") if line.startswith("training the chosen model [")]
        assert chosen and "1000/1000" in chosen[-1], "no bar for the chosen model's training:\n" + text[-2000:]
    print("terminal_check: progress drawn on a terminal (%d frames; %d within a fit; training %d), none when piped"
          % (len(frames), len(within), len(training)))


if __name__ == "__main__":
    main()
