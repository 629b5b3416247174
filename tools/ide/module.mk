# The group IDE: a web page (tools/ide/web, built with npm and esbuild, then
# compiled into the program) and its server over the client library.

LIBRARIES += aseba_ide
aseba_ide_SOURCES := tools/ide/requests.cpp tools/ide/network_worker.cpp tools/ide/workspace.cpp \
                     tools/ide/binary_file.cpp tools/ide/arena_link.cpp tools/ide/ide_server.cpp \
                     tools/ide/background_worker.cpp \
                     tools/ide/web_server.cpp
# websocketpp 0.8.2's headers do not compile as C++20 (web_server.cpp says
# why); this one file is C++17 and nothing of websocketpp leaves it.
EXTRA_CFLAGS_tools/ide/web_server := -std=c++17

PROGRAMS += aseba-ide
aseba-ide_SOURCES := tools/ide/main.cpp $(BUILD)/gen/ide_web_assets.cpp
aseba-ide_LIBS := aseba_ide aseba_client aseba_compiler aseba_node
aseba-ide_LDLIBS := -lpugixml -pthread

# The page: npm installs the packages of the lockfile (once, and again when
# the lockfile changes), esbuild bundles them, and the files become a C++
# source.
IDE_WEB := tools/ide/web
IDE_WEB_SOURCES := $(wildcard $(IDE_WEB)/src/*) $(IDE_WEB)/build.mjs
$(IDE_WEB)/node_modules/.package-lock.json: $(IDE_WEB)/package.json $(IDE_WEB)/package-lock.json | $(DEPS_STAMP)
	cd $(IDE_WEB) && npm ci --no-audit --no-fund --loglevel=error
	@touch $@
$(BUILD)/ide-web/index.html: $(IDE_WEB_SOURCES) $(IDE_WEB)/node_modules/.package-lock.json
	@rm -rf $(BUILD)/ide-web
	node $(IDE_WEB)/build.mjs $(BUILD)/ide-web
$(BUILD)/gen/ide_web_assets.cpp: $(BUILD)/ide-web/index.html scripts/embed-files.py
	@mkdir -p $(@D)
	scripts/embed-files.py $@ $(BUILD)/ide-web
