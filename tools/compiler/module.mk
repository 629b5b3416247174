# The Aseba compiler library: source text and a target description in,
# bytecode out (language.md), plus target presets, project files, error
# rendering and the disassembler shared with the other host tools.
LIBRARIES += aseba_compiler
aseba_compiler_SOURCES := \
    tools/compiler/lexer.cpp \
    tools/compiler/parser.cpp \
    tools/compiler/compilation.cpp \
    tools/compiler/locals.cpp \
    tools/compiler/analysis.cpp \
    tools/compiler/optimizer.cpp \
    tools/compiler/codegen.cpp \
    tools/compiler/linker.cpp \
    tools/compiler/compiler.cpp \
    tools/compiler/target.cpp \
    tools/compiler/target_presets.cpp \
    tools/compiler/target_json.cpp \
    tools/compiler/aesl.cpp \
    tools/compiler/disassembler.cpp \
    tools/compiler/error_format.cpp \
    tools/compiler/program_file.cpp
# .aesl projects are read and written by pugixml (Debian libpugixml-dev),
# target descriptions by nlohmann-json (header only).
aseba_compiler_LDLIBS := -lpugixml
# The e-puck preset lists the firmware's own native table, so both agree.
aseba_compiler_SOURCES += robots/epuck/epuck_natives.c
