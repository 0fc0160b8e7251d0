# Two entry points: `make demo` (the main job) and `make test`. Each installs what it needs and is safe to rerun.
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed-$(shell cat pyproject.toml scripts/system-deps.sh | sha1sum | cut -c1-12)

.PHONY: demo test setup lint clean model side-model

demo: setup
	$(BIN)/station run --camera sim --frames 200

test: setup
	$(BIN)/python -m pytest

lint: setup
	$(BIN)/ruff check .

setup: $(STAMP)

$(STAMP): pyproject.toml scripts/system-deps.sh
	scripts/system-deps.sh
	test -x $(BIN)/python || python3 -m venv $(VENV)
	$(BIN)/pip install -q --upgrade pip
	# torch first, pinned: it comes from the local CPU wheel; an unpinned torch pulls a multi-GB CUDA build.
	$(BIN)/pip install -q torch==2.13.0
	$(BIN)/pip install -q -e '.[dev]'
	rm -f $(VENV)/.installed-*
	touch $@

clean:
	rm -rf $(VENV)

# The shipped model from nothing (render, train, variation model, held-out evaluation, copy to model/weights/default); hours.
model: setup
	scripts/make-model.sh

# The second camera's model (a side camera at belt level: [second_camera] in station.toml), from nothing; 1.5-2 h.
side-model: setup
	scripts/make-side-model.sh
