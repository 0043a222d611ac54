"""Model clients shared by the planners (`agent`) and the VLM perception path.

JSON over HTTP with retries (`http`), the authenticated OpenAI-compatible and Anthropic
clients (`clients`) and the JSON-schema `response_format` dialects (`formats`). Nothing
here knows about plans or scene graphs.
"""

from verigraph.llm.clients import anthropic_client, openai_client
from verigraph.llm.formats import RESPONSE_FORMATS, ResponseFormat, response_format_field
from verigraph.llm.http import JsonHttpClient, LLMEndpointError

__all__ = ["RESPONSE_FORMATS", "JsonHttpClient", "LLMEndpointError", "ResponseFormat",
           "anthropic_client", "openai_client", "response_format_field"]
