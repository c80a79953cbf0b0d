"""`scripts/experiment stability DIR`: how firmly each trend line of a preset output stands.

A trend line's verdict (docs/results.md) comes from one sample of runs per setting, the
thesis's 10 or 15. Where a result is all or nothing per run (a leader arrives with its whole
chain or alone), another 15 seeds can turn "increasing" into "mixed". This splits an output
with many runs per setting (scripts/experiment run PRESET --runs 240) into consecutive blocks
of the preset's run count, by run index (block b: runs b*N ... b*N+N-1, i.e. the seeds
seed_base + b*N ...), judges every block as the page judges the whole, and prints per line how
many blocks read each way, then the verdict over all runs. Only complete blocks count."""

import json
import os

from swarm_transport import experiment_presets as presets
from swarm_transport import experiment_stats as stats
from swarm_transport import experiment_verdicts as verdicts


def load_output(out_dir):
    """(preset, runs) of an experiment output directory (one with experiment.json)."""
    meta_path = os.path.join(out_dir, 'experiment.json')
    if not os.path.isfile(meta_path):
        raise presets.PresetError('%s is not an experiment output (no experiment.json)'
                                  % out_dir)
    with open(meta_path) as f:
        meta = json.load(f)
    preset = presets.validate(meta['preset'], meta['preset']['name'])
    try:  # the expectations and the run count as the preset says now (the output's 'runs'
        # is what this run was asked for)
        current = presets.load_preset(preset['name'])
        preset['expect'], preset['runs'] = current['expect'], current['runs']
    except presets.PresetError:
        pass
    return preset, stats.collect(preset, out_dir)


def blocks(runs, size):
    """[[run, ...] per block]: the runs of block b are those with run index in
    [b*size, (b+1)*size) of every setting; a block counts only when every setting that has runs
    has all `size` of them there."""
    settings = sorted({r['setting'] for r in runs})
    top = max((r['run'] for r in runs), default=-1)
    out = []
    for b in range((top + 1) // size):
        mine = [r for r in runs if b * size <= r['run'] < (b + 1) * size]
        if all(sum(r['setting'] == s for r in mine) == size for s in settings):
            out.append(mine)
    return out


def _summary(preset, runs):
    return {(row['setting'], row['metric']): row for row in stats.summarize(preset, runs)}


def stability(preset, runs, size):
    """[{'line', 'all', 'counts': {verdict kind: blocks}, 'agree': blocks, 'blocks': n}] per
    trend line, in the page's order. 'line' is the page's text over all runs; 'all' its
    verdict ('agrees'/'differs')."""
    whole = verdicts.trend_results(preset, _summary(preset, runs))
    per_block = [verdicts.trend_results(preset, _summary(preset, blk))
                 for blk in blocks(runs, size)]
    out = []
    for i, w in enumerate(whole):
        counts, agree = {}, 0
        for res in per_block:
            if i >= len(res):
                continue
            kind = res[i]['measured'].replace('_', ' ')
            counts[kind] = counts.get(kind, 0) + 1
            agree += res[i]['verdict'] == 'agrees'
        out.append({'line': w['text'], 'all': w['verdict'], 'counts': counts,
                    'agree': agree, 'blocks': len(per_block)})
    return out


def cmd_stability(out_dir, size=None):
    preset, runs = load_output(out_dir)
    size = size or preset['runs']
    if size < 2:
        raise presets.PresetError('--block must be >= 2')
    n = len(blocks(runs, size))
    if n < 2:
        raise presets.PresetError(
            '%s has %d complete block(s) of %d runs per setting; run the preset with '
            '--runs %d or more (e.g. scripts/experiment run %s --runs %d --out %s)'
            % (out_dir, n, size, 2 * size, preset['name'], 16 * size, out_dir))
    rows = stability(preset, runs, size)
    print('%s: %d blocks of %d runs per setting (%d runs per setting in all)'
          % (preset['name'], n, size, n * size))
    for r in rows:
        kinds = ', '.join('%s %d' % (k, c) for k, c in
                          sorted(r['counts'].items(), key=lambda kc: -kc[1]))
        print('- %s\n  blocks: agrees in %d of %d (measured: %s)'
              % (r['line'], r['agree'], r['blocks'], kinds))
    print('RESULT preset=%s blocks=%d block_runs=%d lines=%d firm=%d'
          % (preset['name'], n, size, len(rows),
             sum(r['agree'] in (0, r['blocks']) for r in rows)))
    return 0
