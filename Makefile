# Sylva — build, test, bench, demo and install. `make help` lists the targets.
CC      = gcc
BUILD   = build
PREFIX  = /usr/local
SAN     =
JOBS   ?= $(shell nproc 2>/dev/null || echo 2)

VERSION := $(shell sed -n 's/^#define SYLVA_VERSION "\(.*\)"/\1/p' include/sylva/sylva.h)
WARN    := -Wall -Wextra -Werror
# The sanitizer build keeps line tables only (-g1: what a report's stack needs; a quarter less
# compile time than -g). The release objects are position-independent, so the same objects make
# the program, libsylva.a and the Python extension's shared object (make python); without
# semantic interposition the calls inside the library stay direct and inlinable, as in -fPIE.
# The sanitizer build is clang's: its runtime (ASan with UBSan in one) is linked statically, where
# gcc's two shared runtimes cost a third more CPU at each start (the tests start it thousands of
# times; LeakSanitizer's exit scan also reads libubsan's untouched 6 MB of globals).
ifeq ($(SAN),1)
CC      := clang
OPT     := -O1 -g1 -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
else ifeq ($(SAN),thread)
# ThreadSanitizer (make BUILD=build-tsan SAN=thread sylva units; tests/run-tsan): the threads'
# shared writes checked. Not part of make test: a third tree to build.
CC      := clang
OPT     := -O1 -g1 -fsanitize=thread -fno-omit-frame-pointer
else
OPT     := -O2 -g -fPIC -fno-semantic-interposition
endif
CFLAGS   = -std=c11 $(OPT) $(WARN) -D_GNU_SOURCE -pthread -MMD -MP \
           -Iinclude -Isrc -I$(BUILD)/gen $(PKG_CFLAGS) $(MPI_CFLAGS)
PKGS    := cglm libpng libxml-2.0
# Asked once (:=) when the packages are there, not at each recipe: a recursive $(shell) ran
# pkg-config for every object (about 5 s of CPU a tree). Before `make deps` has installed
# them, at each use, so that the objects this same make builds after it get the flags.
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   = $(shell pkg-config --libs $(PKGS) 2>/dev/null)
LDLIBS   = $(PKG_LIBS) -lembree3 -lmeshoptimizer -lm -pthread $(MPI_LIBS)
# The CLI's own: libmicrohttpd serves `sylva view` (docs/view.md); libsylva does not use it.
CLI_PKGS := libmicrohttpd
CLI_LIBS   = $(shell pkg-config --libs $(CLI_PKGS) 2>/dev/null)
CLI_CFLAGS = $(shell pkg-config --cflags $(CLI_PKGS) 2>/dev/null)
ifeq ($(shell pkg-config --exists $(PKGS) $(CLI_PKGS) 2>/dev/null && echo yes),yes)
PKG_CFLAGS := $(PKG_CFLAGS)
PKG_LIBS   := $(PKG_LIBS)
CLI_LIBS   := $(CLI_LIBS)
CLI_CFLAGS := $(CLI_CFLAGS)
endif
# Programs are linked by lld when it is there (tools/deps.sh installs it): a tree links about 70
# programs against the whole library (sylva, the unit tests, the fuzz replays), and under ASan
# lld takes about half GNU ld's CPU for each (docs/testing.md, How long it takes).
LDFLAGS := $(if $(shell command -v ld.lld 2>/dev/null),-fuse-ld=lld)
$(BUILD)/src/cli/%.o build-fuzz/obj/src/cli/%.o: PKG_CFLAGS += $(CLI_CFLAGS)
# Where `sylva view` finds its page (web/, with three.js from npm ci --prefix web); SYLVA_WEB overrides.
$(BUILD)/src/cli/cmd_view.o: CFLAGS += -DSYL_WEB_DIR='"$(CURDIR)/web"'
# the preview's lines joined in the very arithmetic of web/scene.js's joinStraight: no fused multiply-adds
$(BUILD)/src/cli/view_preview.o: CFLAGS += -ffp-contract=off

# MPI (docs/distributed.md): on when mpicc is found (make MPI=0 builds without it). Only then
# is src/eco/mpi.c compiled, with mpicc's flags; src/eco/mpi_none.c stands in otherwise.
MPI     ?= $(if $(shell command -v mpicc 2>/dev/null),1,0)
ALL_LIB_SRC := $(filter-out src/cli/%,$(wildcard src/*/*.c))
NOMPI_LIB_SRC := $(filter-out src/eco/mpi.c,$(ALL_LIB_SRC))
ifeq ($(MPI),1)
MPI_CFLAGS := $(shell mpicc --showme:compile 2>/dev/null)
MPI_LIBS   := $(shell mpicc --showme:link 2>/dev/null)
LIB_SRC := $(filter-out src/eco/mpi_none.c,$(ALL_LIB_SRC))
else
LIB_SRC := $(NOMPI_LIB_SRC)
endif
CLI_SRC := $(wildcard src/cli/*.c)
GEN_SRC := $(BUILD)/gen/parser.c $(BUILD)/gen/lexer.c
LIB_OBJ := $(LIB_SRC:%.c=$(BUILD)/%.o) $(GEN_SRC:.c=.o)
CLI_OBJ := $(CLI_SRC:%.c=$(BUILD)/%.o)
UNIT_SRC := $(wildcard tests/unit/test_*.c)
UNIT_BIN := $(UNIT_SRC:tests/unit/%.c=$(BUILD)/tests/%)
REPLAY_BIN := $(patsubst tests/fuzz/fuzz_%.c,$(BUILD)/fuzz/replay_%,$(wildcard tests/fuzz/fuzz_*.c))
DEPS_OK := $(BUILD)/.deps-ok

.PHONY: all deps test test-fast test-asan fuzz fuzz-build bench demo gallery install clean help units python python-lib blender-addon
all: $(BUILD)/sylva $(BUILD)/libsylva.a

help:
	@echo "make            build build/sylva and build/libsylva.a"
	@echo "make deps       install missing Debian packages (as root)"
	@echo "make test       every suite, again under ASan+UBSan, with the fuzzers' inputs replayed"
	@echo "make test-fast  the same tests once, without sanitizers"
	@echo "make test-quick the edit loop: unit, case and golden tests of the release build"
	@echo "make test-times the 20 slowest tests, by CPU time"
	@echo "make fuzz       a fuzz campaign: every harness FUZZ_SECONDS long (default 300)"
	@echo "make test-fuzz  a short search: every harness FUZZ_TEST_SECONDS long (default 3; clang)"
	@echo "make bench      speed figures against peer tools"
	@echo "make demo       render every example into out/ (pictures, meshes, out/gallery.md), an ecosystem,"
	@echo "                terrain maps, a LOD chain, a wind file and an animation"
	@echo "make gallery    render every example into docs/gallery/ and write docs/gallery.md"
	@echo "make install PREFIX=/usr/local"
	@echo "make python     the Python package in place (python/sylva; docs/python.md)"
	@echo "make blender-addon  build/sylva-blender.zip, the Blender add-on (docs/blender.md)"

deps:
	@tools/deps.sh
$(DEPS_OK):
	@mkdir -p $(BUILD)
	@tools/deps.sh
	@touch $@

$(BUILD)/gen/parser.c: grammar/parser.y | $(DEPS_OK)
	@mkdir -p $(@D)
	bison -Wall -Werror -d -o $@ $<
$(BUILD)/gen/parser.h: $(BUILD)/gen/parser.c
$(BUILD)/gen/lexer.c: grammar/lexer.l $(BUILD)/gen/parser.h | $(DEPS_OK)
	@mkdir -p $(@D)
	flex --header-file=$(BUILD)/gen/lexer.h -o $@ $<
$(BUILD)/gen/lexer.h: $(BUILD)/gen/lexer.c

# Generated code is not ours to lint.
$(BUILD)/gen/%.o: $(BUILD)/gen/%.c $(BUILD)/.cflags
	$(CC) $(CFLAGS) -Wno-unused-function -Wno-sign-compare -Wno-unused-parameter -c -o $@ $<
$(BUILD)/src/lang/parse.o: $(BUILD)/gen/lexer.h $(BUILD)/gen/parser.h
$(BUILD)/%.o: %.c $(BUILD)/.cflags | $(DEPS_OK) $(BUILD)/gen/parser.h
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -c -o $@ $<
# The flags a tree was compiled with: when they change (say -fPIC added), its objects are remade.
# Expanded here, once: a target's own additions (the CLI's libmicrohttpd flags) must not count.
TREE_FLAGS := $(CC) $(CFLAGS)
$(BUILD)/.cflags: FORCE
	@mkdir -p $(@D)
	@echo '$(TREE_FLAGS)' | cmp -s - $@ || echo '$(TREE_FLAGS)' > $@
FORCE:

# libsylva.a, the installed library, exports the public API only: every object is linked into
# one (ld -r) whose globals are made local except the syl_ names the public headers declare,
# so a program's own yyparse, tree_free or arena_alloc cannot collide with ours, nor can it
# call our internals (tests/run-embed checks it). The unit tests call internal functions, and
# the CLI the lowest layer's helpers (util: the output writer, the JSON escaper): they link the
# plain objects in libsylva-internal.a.
$(BUILD)/libsylva-internal.a: $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^
define public_archive # $(call public_archive,OBJECTS): the recipe of such an archive, $@
	@rm -f $@
	ld -r -o $@.all.o $(1)
	grep -ohE '\bsyl_[a-z0-9_]+' include/sylva/*.h | sort -u > $@.syms
	objcopy --keep-global-symbols=$@.syms $@.all.o $@.api.o
	ar rcs $@ $@.api.o
	@rm -f $@.all.o $@.api.o $@.syms
endef
$(BUILD)/libsylva.a: $(LIB_OBJ) $(wildcard include/sylva/*.h)
	$(call public_archive,$(LIB_OBJ))
# The same library without MPI, for the Python extension: a Python process does not start MPI.
NOMPI_LIB_OBJ := $(filter-out $(BUILD)/src/eco/mpi.o,$(LIB_OBJ)) $(BUILD)/src/eco/mpi_none.o
$(BUILD)/libsylva-nompi.a: $(sort $(NOMPI_LIB_OBJ)) $(wildcard include/sylva/*.h)
	$(call public_archive,$(sort $(NOMPI_LIB_OBJ)))
# The command links only what every command needs (libc, libm, libpng): Embree, libxml2,
# meshoptimizer, OpenMPI and libmicrohttpd are bound on first use (util/lazylib.h), so a
# command that needs none of them starts without loading them (docs/architecture.md, Start-up).
BIN_LDLIBS = $(shell pkg-config --libs libpng 2>/dev/null) -lm -pthread
# Except Embree in the sanitizer build: when it is opened by dlopen, LeakSanitizer's scan at
# exit crashes now and then ("Tracer caught signal 11", `sylva terrain --maps` 3 runs in 6;
# none in 10 with Embree loaded at start).
# The sanitizer build's program is not position-independent: as a PIE, the loader applied
# 180,000 relocations to the sanitizers' tables of globals at each start (55 of its 160 ms of
# CPU, and the tests start it thousands of times).
ifeq ($(SAN),1)
BIN_LDLIBS += -Wl,--push-state,--no-as-needed -lembree3 -Wl,--pop-state -no-pie
endif
$(BUILD)/sylva: $(CLI_OBJ) $(BUILD)/libsylva-internal.a
	$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(BIN_LDLIBS)
# The test-only fault switches (src/cli/testfaults.h) are compiled into $(BUILD)/sylva, which
# the tests run, and left out of the binary make install installs, $(BUILD)/installed/sylva.
$(BUILD)/src/cli/testfaults.o: CFLAGS += -DSYL_TEST_FAULTS
$(BUILD)/src/cli/testfaults-none.o: src/cli/testfaults.c | $(DEPS_OK) $(BUILD)/gen/parser.h
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -c -o $@ $<
$(BUILD)/installed/sylva: $(filter-out $(BUILD)/src/cli/testfaults.o,$(CLI_OBJ)) $(BUILD)/src/cli/testfaults-none.o \
                          $(BUILD)/libsylva-internal.a
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(BIN_LDLIBS)

# ---- tests ----
$(BUILD)/tests/%: tests/unit/%.c tests/unit/unit.h $(BUILD)/libsylva-internal.a
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) -Wno-unused-parameter -o $@ $< $(BUILD)/libsylva-internal.a $(LDLIBS) -lcmocka
# test_cli reads the command line's tables: it links the CLI's objects too (not its main).
$(BUILD)/tests/test_cli: tests/unit/test_cli.c tests/unit/unit.h $(filter-out $(BUILD)/src/cli/main.o,$(CLI_OBJ)) \
                         $(BUILD)/libsylva-internal.a
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) -Wno-unused-parameter -o $@ $< $(filter %.o,$^) $(BUILD)/libsylva-internal.a $(LDLIBS) $(CLI_LIBS) -lcmocka
units: $(UNIT_BIN) $(REPLAY_BIN)
# Each fuzz harness, linked with a plain main that feeds it the files it is given
# (tests/fuzz/replay.c), built by the tree's own compiler: make test replays the seeds and the
# kept inputs under ASan+UBSan (tests/fuzz/replay) without the clang tree, which only make fuzz needs.
$(BUILD)/fuzz/replay_%: tests/fuzz/fuzz_%.c tests/fuzz/replay.c tests/fuzz/fuzz.h $(BUILD)/fuzz/libcli.a $(BUILD)/libsylva-internal.a
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) $(CLI_CFLAGS) -Wno-unused-function -Wno-sign-compare \
	    -Wno-unused-parameter -o $@ $< tests/fuzz/replay.c $(BUILD)/fuzz/libcli.a $(BUILD)/libsylva-internal.a $(LDLIBS) $(CLI_LIBS)
# The CLI without its main, as an archive: a harness takes the members it calls (fuzz_cli: all).
$(BUILD)/fuzz/libcli.a: $(filter-out $(BUILD)/src/cli/main.o,$(CLI_OBJ))
	@mkdir -p $(@D)
	@rm -f $@
	ar rcs $@ $^

# The test targets build with -j$(JOBS) whatever -j make itself was given (.ci/run gives none).
# make test builds its two trees at once under one job server (the packages checked first,
# once), then tests/run-all runs the release and the ASan pass side by side (JOBS > 1), a line
# per job as it ends (docs/testing.md).
test-quick:
	@$(MAKE) --no-print-directory -j$(JOBS) all units
	@JOBS=$(JOBS) tests/run-all --only units,cases,golden $(BUILD)
test-fast:
	@$(MAKE) --no-print-directory -j$(JOBS) all units
	@$(MAKE) --no-print-directory -j$(JOBS) blender-addon
	@JOBS=$(JOBS) tests/run-all $(BUILD)
# ThreadSanitizer over the threaded derivation (not in make test: a third tree to build).
test-tsan:
	@$(MAKE) --no-print-directory -j$(JOBS) BUILD=build-tsan SAN=thread build-tsan/sylva build-tsan/tests/test_stochastic
	@build-tsan/tests/test_stochastic && for c in threads threads_split inplace; do \
	    TSAN_OPTIONS=halt_on_error=1 tests/run-cases build-tsan/sylva tests/cases/$$c.test || exit 1; done
test-asan:
	@$(MAKE) --no-print-directory -j$(JOBS) BUILD=build-asan SAN=1 all units
	@JOBS=$(JOBS) tests/run-all build-asan
test:
	@$(MAKE) --no-print-directory $(DEPS_OK)
	@t0=$$(date +%s); $(MAKE) --no-print-directory -j$(JOBS) test-build-release test-build-asan blender-addon && \
	    echo "make test: built $(BUILD)/, build-asan/ and the Blender add-on in $$(( $$(date +%s) - t0 )) s"
	@JOBS=$(JOBS) tests/run-all $(BUILD) build-asan
# The libFuzzer harnesses searching FUZZ_TEST_SECONDS each (make test replays their inputs only).
test-fuzz: fuzz-build
	@JOBS=$(JOBS) FUZZ_SECONDS=$(FUZZ_TEST_SECONDS) tests/run-all --only none --fuzz build-fuzz
.PHONY: test-tsan test-build-release test-build-asan test-build-fuzz test-times test-quick test-fuzz
test-build-release:
	@$(MAKE) --no-print-directory all units
test-build-asan:
	@$(MAKE) --no-print-directory BUILD=build-asan SAN=1 all units
test-build-fuzz:
	@$(MAKE) --no-print-directory fuzz-build
# The 20 slowest tests of build/ by CPU time (tools/test-times; docs/testing.md).
test-times:
	@$(MAKE) --no-print-directory -j$(JOBS) all units
	@tools/test-times $(BUILD) 20

# ---- fuzzing (clang + libFuzzer) ----
# One harness per reader: tests/fuzz/fuzz_NAME.c becomes build-fuzz/fuzz_NAME, linked against
# the library (and the CLI without its main) built once with the sanitizers; tests/fuzz/harnesses
# lists them with their dictionary. A new reader's harness is one file there and one line here.
FUZZ_CFLAGS = -std=c11 -O1 -g1 -Wall -Wextra -D_GNU_SOURCE -pthread -Iinclude -Isrc -Ibuild-fuzz/gen $(PKG_CFLAGS) \
               -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer \
               -Wno-unused-function -Wno-sign-compare -Wno-unused-parameter
FUZZ_HARNESS := $(patsubst tests/fuzz/%.c,build-fuzz/%,$(wildcard tests/fuzz/fuzz_*.c))
FUZZ_LIB_SRC := $(NOMPI_LIB_SRC) $(filter-out src/cli/main.c,$(CLI_SRC))
FUZZ_LIB_OBJ := $(FUZZ_LIB_SRC:%.c=build-fuzz/obj/%.o) build-fuzz/obj/gen/parser.o build-fuzz/obj/gen/lexer.o
FUZZ_SECONDS ?= 300
FUZZ_TEST_SECONDS ?= 3
build-fuzz/gen/.made: grammar/lexer.l grammar/parser.y | $(DEPS_OK)
	@mkdir -p $(@D)
	bison -Wall -Werror -d -o build-fuzz/gen/parser.c grammar/parser.y
	flex --header-file=build-fuzz/gen/lexer.h -o build-fuzz/gen/lexer.c grammar/lexer.l
	@touch $@
build-fuzz/obj/gen/parser.o build-fuzz/obj/gen/lexer.o: build-fuzz/obj/gen/%.o: build-fuzz/gen/.made
	@mkdir -p $(@D)
	clang $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link -MMD -MP -c -o $@ build-fuzz/gen/$*.c
build-fuzz/obj/%.o: %.c build-fuzz/gen/.made
	@mkdir -p $(@D)
	clang $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link -MMD -MP -c -o $@ $<
build-fuzz/libsylva-fuzz.a: $(FUZZ_LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^
build-fuzz/fuzz_%: tests/fuzz/fuzz_%.c tests/fuzz/fuzz.h build-fuzz/libsylva-fuzz.a
	clang $(FUZZ_CFLAGS) -fsanitize=fuzzer -o $@ $< build-fuzz/libsylva-fuzz.a $(filter-out $(MPI_LIBS),$(LDLIBS)) $(CLI_LIBS)
fuzz-build: $(FUZZ_HARNESS)
# A campaign: every harness for FUZZ_SECONDS, its corpus kept in tests/fuzz/corpus/NAME/.
fuzz: $(FUZZ_HARNESS)
	@tests/fuzz/run-all build-fuzz $(FUZZ_SECONDS) --keep
-include $(FUZZ_LIB_SRC:%.c=build-fuzz/obj/%.d) build-fuzz/obj/gen/parser.d build-fuzz/obj/gen/lexer.d

# ---- Python (docs/python.md) ----
# The extension links build/libsylva-nompi.a, the library without MPI (python/setup.py runs
# `make python-lib`, which brings it up to date); `make python` builds it in place,
# so PYTHONPATH=python finds the package; `pip install ./python` installs it into a venv.
PYTHON ?= /usr/bin/python3
python-lib:
	@$(MAKE) --no-print-directory -j$(JOBS) build/libsylva-nompi.a
python: python-lib
	cd python && $(PYTHON) setup.py -q build_ext --inplace

# The Blender add-on (docs/blender.md): blender/ with the sylva package built for Blender's
# Python (Debian's Blender 3.4 runs the system's Python 3.11), zipped for Preferences → Install.
BLENDER_LIBRARY = weberpenn sot pafco strands curvetree hybrid picek seeds abop scenes ecosystem
blender-addon: python
	@rm -rf $(BUILD)/blender && mkdir -p $(BUILD)/blender/sylva_blender/sylva
	cp blender/sylva_blender/*.py blender/blender_manifest.toml $(BUILD)/blender/sylva_blender/
	cp python/sylva/*.py python/sylva/py.typed python/sylva/_core*.so $(BUILD)/blender/sylva_blender/sylva/
	@# the species library: the examples' model files and what they read, each with its gallery picture
	mkdir -p $(BUILD)/blender/sylva_blender/library/gallery
	cp -r $(addprefix examples/,$(BLENDER_LIBRARY)) $(BUILD)/blender/sylva_blender/library/
	cp docs/gallery/*.png $(BUILD)/blender/sylva_blender/library/gallery/
	@rm -f $(BUILD)/sylva-blender.zip
	cd $(BUILD)/blender && $(PYTHON) -m zipfile -c ../sylva-blender.zip sylva_blender
	@echo "$(BUILD)/sylva-blender.zip: Blender → Preferences → Add-ons → Install…"

# ---- user-facing ----
bench: all
	@bench/run

demo: all
	@tools/demo $(BUILD)/sylva

# The pictures are kept small for the repository: 384 x 384, quantized when pngquant is there.
gallery: all
	@tools/gallery --sylva $(BUILD)/sylva --size 384 --small --md docs/gallery.md docs/gallery

# The page of `sylva view` and the files of three.js it imports (docs/view.md), installed in
# PREFIX/share/sylva/web, where the installed sylva looks beside its bin/ (cmd_view.c).
VIEW_WEB   := web/index.html $(wildcard web/*.js) web/style.css
VIEW_THREE := LICENSE package.json build/three.module.js examples/jsm/loaders/GLTFLoader.js \
              examples/jsm/controls/OrbitControls.js examples/jsm/utils/BufferGeometryUtils.js
install: all $(BUILD)/installed/sylva
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/include/sylva
	install -m 755 $(BUILD)/installed/sylva $(DESTDIR)$(PREFIX)/bin/sylva
	install -m 644 $(BUILD)/libsylva.a $(DESTDIR)$(PREFIX)/lib/libsylva.a
	install -m 644 include/sylva/*.h $(DESTDIR)$(PREFIX)/include/sylva/
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' -e 's|@MPI_LIBS@|$(MPI_LIBS)|' tools/sylva.pc.in \
	    > $(DESTDIR)$(PREFIX)/lib/pkgconfig/sylva.pc
	install -d $(DESTDIR)$(PREFIX)/share/sylva/web
	install -m 644 $(VIEW_WEB) $(DESTDIR)$(PREFIX)/share/sylva/web/
	for f in $(VIEW_THREE); do install -D -m 644 web/node_modules/three/$$f $(DESTDIR)$(PREFIX)/share/sylva/web/node_modules/three/$$f || exit 1; done

clean:
	rm -rf build build-asan build-fuzz build-pic out python/build python/sylva/*.so

-include $(LIB_OBJ:.o=.d) $(CLI_OBJ:.o=.d) $(BUILD)/src/cli/testfaults-none.d $(REPLAY_BIN:=.d)
