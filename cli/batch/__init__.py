"""Batches: a corpus of sentences through the pipeline, in this process or on a Dask cluster.

``run_corpus(path, Options(out=DIR))`` animates every line into sharded
folders under ``DIR``, one record per line in ``DIR/manifest.jsonl`` as the
results arrive, and skips the lines an earlier run finished; ``jobs`` or
``scheduler`` spread the chunks of lines over Dask workers
(``pip install 'text2anim[cluster]'``).
"""
from __future__ import annotations

from .corpus import CorpusError, Item, chunks, load_corpus, text_hash
from .errors import BatchError
from .lines import Options, compare, run_line, shard_path
from .manifest import Manifest
from .runner import DEFAULT_CHUNK, Outcome, run_corpus
from .summary import Summary

__all__ = ["BatchError", "CorpusError", "DEFAULT_CHUNK", "Item", "Manifest", "Options", "Outcome", "Summary",
           "chunks", "compare", "load_corpus", "run_corpus", "run_line", "shard_path", "text_hash"]
