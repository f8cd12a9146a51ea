/* syl_pafco_build: Pafčo's tree from a `pafco` block or a Pafčo file (docs/pafco.md);
 * syl_pafco_validate: the block's check for `sylva check`. */
#include <stdio.h>

#include "lang/textures.h"
#include "skeleton/store.h"
#include "pafco/pafco.h"
#include "sylva/trees.h"
#include "lang/program.h"

int syl_pafco_validate(const SylProgram *p, FILE *diag) {
    return syl_program_kind(p) == SYL_MODEL_PAFCO ? pafco_params_check(p, diag) : 0;
}

/* The textures of the model's own (lang/textures.c: K_SUBOR is the bark line, tiled
 * H_TEX_MUL x V_TEX_MUL unless the line says; TEX_SUBORY the leaf line): with TEX_SUBORY,
 * the leaf materials 1..n pafco_build made, one a file, each leaf given one at random there.
 * SYL_OK, or the error (reported). */
static int textures(const SylProgram *p, const PafcoParams *P, SylSkeleton *sk, uint64_t seed, FILE *diag) {
    SylTextureSpec tex;
    int st = lang_textures(p, &tex, diag);
    if (st) return st;
    if (!(tex.tile[0] > 0)) tex.tile[0] = (float)P->h_tex, tex.tile[1] = (float)P->v_tex;
    if (P->ntex) {
        for (int k = 0; k < tex.nleaf && 1 + k < sk->nmaterials; k++) sk->materials[1 + k].image = tex.leaf[k];
        tex.nleaf = 0;
    }
    st = syl_skeleton_apply_textures(sk, &tex, seed);
    lang_textures_free(&tex);
    return st;
}

int syl_pafco_build(const SylProgram *p, const SylTreeOptions *opt, SylSkeleton **out) {
    static const SylTreeOptions none = {0};
    if (!opt) opt = &none;
    *out = NULL;
    if (syl_program_kind(p) != SYL_MODEL_PAFCO) {
        program_say(p, opt->diag, DIAG_ERROR, NULL, "'%s' is a %s, not a pafco block", syl_program_name(p),
                    syl_model_kind_name(syl_program_kind(p)));
        return SYL_EUSAGE;
    }
    PafcoParams P;
    if (pafco_params_read(p, &P, opt->diag)) return SYL_EMODEL;
    if (opt->age > 0 && opt->age < 1) P.height *= opt->age; /* growth by height (sylva animate) */
    uint64_t seed = (opt->use_seed ? opt->seed : 1) + opt->seed_offset;
    Budget own, *mem = budget_use(&own, opt->max_memory, opt->budget);
    SylSkeleton *sk = syl_skeleton_new(syl_program_name(p));
    if (!sk) {
        program_say(p, opt->diag, DIAG_ERROR, NULL, "'%s': out of memory for the skeleton", syl_program_name(p));
        return SYL_ELIMIT;
    }
    double nodes, leaves, bytes;
    bool partial;
    if (!pafco_fits(&P, mem, &nodes, &leaves, &bytes, &partial)) { /* refused before a node is made */
        char size[96]; /* a count stopped at the budget gives only its nodes, and them as a least */
        if (partial) snprintf(size, sizeof size, "more than %.0f nodes", nodes);
        else snprintf(size, sizeof size, "up to %.0f nodes and %.0f leaves (%.0f MB)", nodes, leaves, bytes / (1 << 20));
        program_say(p, opt->diag, DIAG_ERROR, NULL, "'%s': the tree may have %s, more than --max-memory allows (%llu MB%s); raise "
                    "the limit with --max-memory, or lower VYSKA_STROMU, SEG_VET, V1G_POCET, V2G_MAX, V3G_MAX or "
                    "LSPH_POCET",
                    syl_program_name(p), size, (unsigned long long)budget_limit_mb(mem), mem == &own ? "" : " in all");
        syl_skeleton_free(sk);
        return SYL_ELIMIT;
    }
    uint64_t before = syl_budget_used(mem);
    int st = pafco_build(&P, seed, mem, sk, NULL, opt->cancel);
    uint64_t charged = syl_budget_used(mem) - before;
    if (st) {
        if (st != SYL_ECANCELED) /* stopped: nothing said */
            program_say(p, opt->diag, DIAG_ERROR, NULL, "'%s' needs more memory than --max-memory allows (%llu MB%s)",
                        syl_program_name(p), (unsigned long long)budget_limit_mb(mem), mem == &own ? "" : " in all");
        budget_release(mem, charged);
        syl_skeleton_free(sk);
        return st;
    }
    if (mem != &own) skeleton_charge(sk, mem, charged);
    else budget_release(mem, charged);
    if ((st = textures(p, &P, sk, seed, opt->diag)) != SYL_OK) {
        syl_skeleton_free(sk);
        return st;
    }
    *out = sk;
    return SYL_OK;
}
