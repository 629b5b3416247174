# The 2007 Aseba paper's Fig. 5 experiment (dangerous-area avoidance) in the
# simulated arena: the runs and measurement (a library, also for
# tests/arena), the dangerous-areas program that writes the CSV and the
# table, and plot.py that draws the figure (docs/experiment.md).
LIBRARIES += aseba_dangerous_areas
aseba_dangerous_areas_SOURCES := experiments/dangerous-areas/experiment.cpp \
                                 experiments/dangerous-areas/report.cpp

PROGRAMS += dangerous-areas
dangerous-areas_SOURCES := experiments/dangerous-areas/main.cpp
# The arena's libraries are epuck-emu's (tools/emulator/module.mk, included later:
# hence `=`).
dangerous-areas_LIBS = aseba_dangerous_areas $(epuck-emu_LIBS)
dangerous-areas_LDLIBS = $(epuck-emu_LDLIBS)

# `make experiment`: the four conditions x 5 seeds of 60 s; writes
# docs/experiment/dangerous-areas.csv and the table in docs/experiment.md,
# then the figure docs/experiment/dangerous-areas.svg from the CSV
# (plot.py, matplotlib). Debian's Python has python3-matplotlib; another
# python3 first on the PATH may not.
PLOT_PYTHON ?= /usr/bin/python3
.PHONY: experiment
experiment: $(BUILD)/host/bin/dangerous-areas | $(EXPERIMENT_DEPS_STAMP)
	$< --out docs/experiment --doc docs/experiment.md
	$(PLOT_PYTHON) experiments/dangerous-areas/plot.py docs/experiment/dangerous-areas.csv \
	    docs/experiment/dangerous-areas.svg
