#!/usr/bin/env python3
"""Seed corpora for the fuzz targets (tests/fuzz/fuzz_targets.h), made from real files.

usage: python3 tools/fuzz_seeds.py BTFLUT_BINARY OUT_FOLDER [SHARED_DATA_FOLDER]

Writes OUT_FOLDER/<target>/<seed> for every target: small crops of the shared captures in
every image format and variant btflut decodes (PNG 8/16-bit, grey, palette, alpha; JPEG
baseline, progressive, grey; TGA raw and run-length; BMP), banks baked by btflut from tiny
datasets (grey, rgb, with a PTM, over the isotropic domain), and the text files of real
datasets (.lp, lights.txt, manifests), scenes, histogram CSVs, model parameters and names.
Small seeds keep each execution fast.
"""
import io
import json
import os
import shutil
import subprocess
import sys
import tempfile

from PIL import Image

btflut, out = sys.argv[1], sys.argv[2]
shared = sys.argv[3] if len(sys.argv) > 3 else None
if shared and not os.path.isdir(shared):
    shared = None


def seed(target, name, data):
    folder = os.path.join(out, target)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), 'wb') as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def run(*args):
    subprocess.run([btflut, *args], check=True, stdout=subprocess.DEVNULL)


work = tempfile.mkdtemp(prefix='btflut-seeds-')
try:
    # Images: crops of real captures (or of a synthetic material when the data is absent).
    run('synth', '--preset', 'plastic', '--geometry', 'rti-9', '--size', '32', '--correlation-length', '6',
        '--albedo-variation', '0.5', '-q', '-o', os.path.join(work, 'tiny'))
    sources = [os.path.join(work, 'tiny', f) for f in sorted(os.listdir(os.path.join(work, 'tiny')))
               if f.endswith('.png') and f != 'mask.png']
    if shared:
        sources += [os.path.join(shared, 'psm-rock', 'rock.3.tga'), os.path.join(shared, 'dome-synth', 'image07.jpg')]
    crops = []
    for path in sources[-3:]:
        im = Image.open(path).convert('RGB')
        w, h = im.size
        crops.append(im.crop((w // 2 - 8, h // 2 - 6, w // 2 + 8, h // 2 + 6)))
    for k, im in enumerate(crops):
        def save(name, image, fmt, **options):
            buffer = io.BytesIO()
            image.save(buffer, fmt, **options)
            seed('image', f'{k}-{name}', buffer.getvalue())
        save('rgb.png', im, 'PNG')
        save('grey.png', im.convert('L'), 'PNG')
        save('palette.png', im.convert('P'), 'PNG')
        save('rgba.png', im.convert('RGBA'), 'PNG')
        save('grey16.png', im.convert('L').convert('I;16'), 'PNG')
        save('base.jpg', im, 'JPEG', quality=90)
        save('prog.jpg', im, 'JPEG', quality=80, progressive=True)
        save('grey.jpg', im.convert('L'), 'JPEG')
        save('raw.tga', im, 'TGA')
        save('rle.tga', im, 'TGA', compression='tga_rle')
        save('rgb.bmp', im, 'BMP')
        save('palette.bmp', im.convert('P'), 'BMP')

    # Banks baked by btflut from tiny datasets: each kind of chunk and domain.
    tiny = os.path.join(work, 'tiny')
    colour = os.path.join(work, 'colour')  # the same set, tinted
    shutil.copytree(tiny, colour)
    for f in os.listdir(colour):
        if f.endswith('.png') and f != 'mask.png':
            grey = Image.open(os.path.join(colour, f)).convert('L')
            Image.merge('RGB', (grey, grey.point(lambda v: v * 3 // 4), grey.point(lambda v: v // 2))).save(
                os.path.join(colour, f))
    for name, folder, args in [('grey', tiny, ['--references', '1']), ('ptm', tiny, ['--references', '1', '--ptm']),
                               ('rgb', colour, ['--colour', 'rgb']),
                               ('blend', colour, ['--colour', 'lrgb', '--references', '3', '--regions', '2', '--quantiles', '16']),
                               ('blend-rgb', colour, ['--colour', 'rgb', '--references', '2', '--quantiles', '8']),
                               ('predictor', tiny, ['--predictor', 'ptm', '--regions', '2', '--quantiles', '16']),
                               # version 5: light models, partial matching, the validated choice
                               ('auto', colour, ['--quantiles', '16']),
                               ('hsh', colour, ['--predictor', 'hsh3', '--colour', 'rgb', '--quantiles', '8']),
                               ('rbf', colour, ['--predictor', 'rbf4c', '--match', '0.5', '--quantiles', '16']),
                               ('bln', tiny, ['--predictor', 'bln3', '--regions', '2', '--quantiles', '16'])]:
        bank = os.path.join(work, name + '.btflut')
        run('bake', folder, '-o', bank, '--grid', '3', '--entries', '16', '-q', *args)
        seed('bank', name + '.btflut', open(bank, 'rb').read())
    # version 6: a target fitted over the light between the measured lights (TFIT), per region
    run('synth', '--preset', 'concrete', '--geometry', 'rti-49', '--size', '16', '--correlation-length', '4', '-q', '-o',
        os.path.join(work, 'dome'))
    run('bake', os.path.join(work, 'dome'), '-o', os.path.join(work, 'fit.btflut'), '--predictor', 'hsh2', '--regions', '2',
        '--grid', '3', '--entries', '16', '--quantiles', '16', '-q')
    seed('bank', 'target-fit.btflut', open(os.path.join(work, 'fit.btflut'), 'rb').read())
    run('synth', '--preset', 'foil', '--size', '16', '--correlation-length', '4', '-q', '-o', os.path.join(work, 'curet'))
    run('bake', os.path.join(work, 'curet'), '-o', os.path.join(work, 'iso.btflut'), '--grid', '2', '--entries', '8', '-q')
    seed('bank', 'isotropic.btflut', open(os.path.join(work, 'iso.btflut'), 'rb').read())
    # version 7: the isotropic domain's target fitted over the pairs (TFIT, one fit)
    run('synth', '--preset', 'concrete', '--geometry', 'btf-9', '--size', '16', '--correlation-length', '4', '-q', '-o',
        os.path.join(work, 'btf'))
    run('bake', os.path.join(work, 'btf'), '-o', os.path.join(work, 'pairs.btflut'), '--domain', 'isotropic', '--grid', '2',
        '--entries', '8', '-q')
    seed('bank', 'pair-fit.btflut', open(os.path.join(work, 'pairs.btflut'), 'rb').read())
    # version 8: a learned predictor (LRND)
    run('bake', colour, '-o', os.path.join(work, 'neural.btflut'), '--predictor', 'neural4', '--colour', 'rgb', '--grid',
        '3', '--entries', '16', '--quantiles', '8', '-q')
    seed('bank', 'learned.btflut', open(os.path.join(work, 'neural.btflut'), 'rb').read())
    # version 9: a learned predictor of views (LRND with its view features), a layer per view
    run('synth', '--preset', 'concrete', '--geometry', 'btf-3', '--size', '16', '--correlation-length', '4', '-q', '-o',
        os.path.join(work, 'btf3'))
    run('bake', os.path.join(work, 'btf3'), '-o', os.path.join(work, 'views.btflut'), '--predictor', 'neural2', '--grid',
        '2', '--entries', '8', '--quantiles', '8', '-q')
    seed('bank', 'learned-views.btflut', open(os.path.join(work, 'views.btflut'), 'rb').read())

    # Text files of real datasets.
    seed('manifest', 'synth.json', open(os.path.join(tiny, 'btflut-dataset.json')).read())
    seed('manifest', 'curet.json', open(os.path.join(work, 'curet', 'btflut-dataset.json')).read())
    seed('lp', 'synth.lp', open(os.path.join(tiny, 'synth.lp')).read())
    if shared:
        seed('lp', 'dome.lp', open(os.path.join(shared, 'dome-synth', 'dirs.lp')).read())
        seed('lights', 'psm-rock.txt', open(os.path.join(shared, 'psm-rock', 'lights.txt')).read())
    seed('lights', 'two.txt', '2\n0 0 1\n0.6 0 0.8\n')
    run('hist', tiny, '--bins', '8', '-o', os.path.join(work, 'h.csv'))
    seed('histograms', 'hist.csv', open(os.path.join(work, 'h.csv')).read())
    run('simulate', '--roughness', '0.4', '--geometry', 'curet-specular', '--bins', '6', '-o', os.path.join(work, 's.csv'))
    seed('histograms', 'simulate.csv', open(os.path.join(work, 's.csv')).read())

    seed('scene', 'scene.json', json.dumps({
        'btflut_scene': 1, 'image': {'width': 64, 'height': 48},
        'camera': {'position': [0, -4, 2.5], 'target': [0, 0, 0], 'up': [0, 0, 1], 'fov_degrees': 45},
        'light': {'direction': [-0.5, -0.6, 0.6]},
        'materials': {'a': 'a.btflut', 'b': {'bank': 'b.btflut', 'images': 'ds'}},
        'interpolation': 'nearest',
        'quads': [{'material': 'a', 'center': [0, 0, 0], 'normal': [0, 0, 1], 'tangent': [1, 0, 0],
                   'size': [4, 4], 'uv_scale': 2, 'mode': 'lut'},
                  {'material': 'b', 'center': [0, 1.2, 0.9], 'normal': [0, -1, 0], 'tangent': [1, 0, 0],
                   'size': [1.6, 1.06], 'mode': 'ptm'}]}, indent=1))
    seed('params', 'mix.json', json.dumps({
        'btflut_model': 1, 'roughness': 0.4, 'brdf': 'mix', 'kd': 0.7, 'ks': 0.3, 'sigma': 0.13, 'ior': 1.5,
        'gain': 0.6, 'method': 'quadrature', 'nodes': 8, 'bins': 64, 'smooth': 0, 'samples': 5000, 'seed': 1,
        'view': {'theta': 0, 'phi': 0}, 'lights': [{'theta': 0, 'phi': 0}, {'theta': 45, 'phi': 90}]}, indent=1))
    seed('params', 'lambert.json', '{"roughness": 0.3}')
    for k, name in enumerate(['tl015 pl000 tv000 pv000.jpg', 'tl075_pl330_tv060_pv120.png', '30,45', ' 89.5 , -720']):
        seed('names', f'{k}.txt', name)
finally:
    shutil.rmtree(work)
