// An embedding program in C++ (the headers' extern "C" is what lets it link), built against
// an installed Sylva by tests/run-embed.
//   plant_cpp MODEL.syl [YEARS]   builds the model (a grow block: YEARS years) and prints
// "kind K", "nodes N", "triangles N"; with YEARS it also asks for the skeleton only and
// checks that the mesh is then absent and the skeleton the same.
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include <sylva/grow.h>
#include <sylva/plant.h>
#include <sylva/sylva.h>

namespace {
struct ProgramFree {
    void operator()(SylProgram *p) const { syl_program_free(p); }
};
using Program = std::unique_ptr<SylProgram, ProgramFree>;

struct Plant {
    SylPlant pl{};
    ~Plant() { syl_plant_free(&pl); }
};

int failures = 0;
void check(bool ok, const char *what) {
    if (!ok) {
        std::fprintf(stderr, "plant.cpp: check failed: %s\n", what);
        failures++;
    }
}
} // namespace

int main(int argc, char **argv) {
    if (argc < 2 || argc > 3) {
        std::fprintf(stderr, "usage: %s MODEL.syl [YEARS]\n", argv[0]);
        return 2;
    }
    SylCompileOptions co{};
    co.diag = stderr;
    int st = 0;
    Program p(syl_compile(argv[1], nullptr, 0, &co, &st));
    if (!p) return st;
    SylPlantOptions po{};
    po.diag = stderr;
    if (argc == 3) {
        po.use_steps = 1;
        po.steps = std::atoi(argv[2]);
    }
    Plant full;
    st = syl_plant_build(p.get(), &po, &full.pl);
    if (st) return st;
    check(full.pl.skeleton != nullptr && full.pl.mesh != nullptr, "a skeleton and a mesh");
    check(full.pl.mesh->nidx > 0 && full.pl.mesh->nidx % 3 == 0, "whole triangles");
    const bool grown = full.pl.kind != SYL_MODEL_LSYSTEM;
    check(grown == (full.pl.string == nullptr), "a string exactly for L-systems");
    if (grown) check(full.pl.grow.metamers > 0, "grow stats filled");
    if (argc == 3) {
        po.until = SYL_PLANT_SKELETON;
        Plant sk;
        st = syl_plant_build(p.get(), &po, &sk.pl);
        check(st == SYL_OK, "the skeleton alone builds");
        check(sk.pl.mesh == nullptr, "no mesh when asked for the skeleton");
        check(sk.pl.skeleton && sk.pl.skeleton->nnodes == full.pl.skeleton->nnodes, "the same skeleton");
        po.until = SYL_PLANT_STRING;
        po.diag = nullptr; /* a grow block refuses, as it should: not worth a message here */
        Plant str;
        st = syl_plant_build(p.get(), &po, &str.pl);
        check(grown ? st == SYL_EUSAGE : st == SYL_OK, "a string only from an L-system");
    }
    static const char *const kinds[] = {"lsystem", "grow", "scene"};
    std::printf("kind %s\nnodes %zu\ntriangles %zu\n", kinds[full.pl.kind], full.pl.skeleton->nnodes,
                full.pl.mesh->nidx / 3);
    return failures ? 1 : 0;
}
